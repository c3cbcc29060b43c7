#!/usr/bin/env bash
# The Ru hemisphere with its asperities from a height map against the paper's layout (about a
# minute): the map's summits (OUT/map: top-view.png, summit-heights.png, summits.csv), the run of
# cases/rough-surface/afm-hemisphere.toml and of cases/ru-rough-sphere/rough-w6-quick.toml, and
# their force and real-area curves overlaid (OUT/plots: force_approach.png, area_approach.png,
# and SVG). The figures of docs/surfaces.md are these, copied by hand.
#   bash scripts/afm-hemisphere.sh [OUT]     (default out/afm-hemisphere)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out/afm-hemisphere}
cargo build --release --quiet
STICTION=./target/release/stiction
mkdir -p "$OUT"
$STICTION surface stats cases/rough-surface/ru-film-256nm.gsf --periodic --threshold 0 --min-spacing 3.5 \
  --out "$OUT/map"
# the plot labels each run by its folder's name
$STICTION run cases/rough-surface/afm-hemisphere.toml --out "$OUT/height-map" --overwrite --quiet
$STICTION run cases/ru-rough-sphere/rough-w6-quick.toml --out "$OUT/paper-layout" --overwrite --quiet
$STICTION plot "$OUT/height-map" "$OUT/paper-layout" --output "$OUT/plots" \
  --title "Ru hemisphere, w = 6 J/m^2: height-map summits vs the paper's layout"
