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
cargo run --release --bin stiction -- run cases/ru-sphere/ru-hemisphere-quick.toml "$@"
echo "results: out/ru-hemisphere-quick/ (history.csv, summary.json, ru-hemisphere-quick.pvd for ParaView)"
