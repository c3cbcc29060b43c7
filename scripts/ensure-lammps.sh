#!/usr/bin/env bash
# Installs LAMMPS (`lmp`) and its potential files from Debian's packages when missing (sourced
# by the test script): `stiction md` runs it, and its tests run a tiny Au asperity with
# /usr/share/lammps/potentials/Au_u3.eam.
if ! command -v lmp >/dev/null 2>&1 || [ ! -f /usr/share/lammps/potentials/Au_u3.eam ]; then
  SUDO=""
  if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
  echo "installing LAMMPS (Debian packages lammps, lammps-data)..." >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends lammps lammps-data >/dev/null
fi
