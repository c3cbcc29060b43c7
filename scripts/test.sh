#!/usr/bin/env bash
# The test command: installs what the tests need (gmsh; OpenMPI and libclang for the `mpi`
# feature; ParaView and Xvfb for the views script; LAMMPS for `stiction md`) if missing, then runs every test of the workspace, and the MPI ensemble test with the
# cargo feature `mpi`. `.ci/run` calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-gmsh.sh
source scripts/ensure-mpi.sh
source scripts/ensure-paraview.sh
source scripts/ensure-lammps.sh
gmsh --version
cargo test --workspace
# the optional MPI build: `mpirun -n 2 stiction ensemble` against the serial aggregate
# (`--workspace`: the same packages as the first run, so that their features, and their builds,
# are the same)
cargo test --workspace --features stiction/mpi --test ensemble --test fit mpi_
