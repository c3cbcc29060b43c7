#!/usr/bin/env bash
# The test command: installs what the tests need (gmsh) if missing, then runs every test of
# the workspace. `.ci/run` calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-gmsh.sh
gmsh --version
cargo test --workspace
