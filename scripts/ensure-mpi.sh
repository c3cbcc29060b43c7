#!/usr/bin/env bash
# Installs OpenMPI and libclang from Debian's packages when they are missing (sourced by the test
# script): the cargo feature `mpi` builds the `mpi` crate, whose bindings need the MPI headers
# (libopenmpi-dev), `mpicc` to find them, and libclang (bindgen); its tests need `mpirun`.
if ! command -v mpirun >/dev/null 2>&1 || ! command -v mpicc >/dev/null 2>&1 \
    || ! ls /usr/lib/llvm-*/lib/libclang*.so* >/dev/null 2>&1; then
  SUDO=""
  if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
  echo "installing OpenMPI and libclang (Debian packages)..." >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq openmpi-bin libopenmpi-dev libclang-dev >/dev/null
fi
# OpenMPI refuses to start as root unless told; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
