#!/usr/bin/env bash
# Sets up a fresh machine (gmsh from Debian's packages, if missing) and runs the main job at
# its quick default, replacing an earlier run of it in out/rough-w6-quick. Extra arguments go
# to `stiction run` (e.g. --set key=value).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-gmsh.sh
cargo build --release --workspace
./target/release/stiction run cases/ru-rough-sphere/rough-w6-quick.toml --overwrite "$@"
echo "results: out/rough-w6-quick/ (history.csv, events.csv, summary.json, rough-w6-quick.pvd and rough-w6-quick_asperities.pvd for ParaView)"
