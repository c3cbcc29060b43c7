#!/usr/bin/env bash
# Molecular dynamics to the rough hemisphere in one go (about 2 minutes on 2 cores, with
# LAMMPS): the quick Au nano-asperity experiment (cases/md/au-asperity-quick.toml) into OUT/md,
# its table fitted into OUT/au-quick.toml (6th-order loading, 7th-order unloading), and the
# rough gold hemisphere (cases/md/au-rough-sphere.toml) run with that calibration into
# OUT/sphere (force and area curves, VTK). The shipped calibration,
# cases/md/calibrations/au-quick.toml, is this chain's, kept by
# cases/md/calibrations/regenerate.sh.
#   bash scripts/au-rough-sphere.sh [OUT]     (default out/au-rough-sphere)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-lammps.sh
OUT=${1:-out/au-rough-sphere}
cargo build --release --quiet
STICTION=./target/release/stiction
mkdir -p "$OUT"
$STICTION md cases/md/au-asperity-quick.toml --out "$OUT/md"
$STICTION calibrate "$OUT/md/force-distance.csv" -o "$OUT/au-quick.toml" --loading-order 6 --unloading-order 7
$STICTION run cases/md/au-rough-sphere.toml --out "$OUT/sphere" --overwrite \
  --set "interfaces.0.config_file=$(realpath "$OUT/au-quick.toml")"
