#!/usr/bin/env bash
# Sets up a fresh machine (gmsh from Debian's packages, if missing) and runs the main job at
# its quick default. Extra arguments go to `stiction run` (e.g. --set key=value).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v gmsh >/dev/null 2>&1; then
  SUDO=""
  if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
  echo "installing gmsh (Debian package)..." >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq gmsh >/dev/null
fi
cargo build --release --workspace
./target/release/stiction run cases/ru-rough-sphere/rough-w6-quick.toml "$@"
echo "results: out/rough-w6-quick/ (history.csv, events.csv, summary.json, rough-w6-quick.pvd and rough-w6-quick_asperities.pvd for ParaView)"
