#!/usr/bin/env bash
# Installs gmsh from Debian's packages when it is not on PATH (sourced by the run and test
# scripts, so a fresh machine needs nothing by hand).
if ! command -v gmsh >/dev/null 2>&1; then
  SUDO=""
  if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
  echo "installing gmsh (Debian package)..." >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq gmsh >/dev/null
fi
