#!/usr/bin/env bash
# Rough vs smooth at the paper's three works of adhesion (a long run, not a test): for each
# w = 1, 3, 6 J/m^2 the rough sphere pressed to 2.0 nm (cases/ru-rough-sphere/rough-w{w}.toml,
# study mesh), the smooth elastic-plastic sphere with Lennard-Jones adhesion and with a
# cohesive zone (cases/ru-sphere/smooth-{lj,cohesive}-w{w}.toml), then per w the force and
# real-area overlays (OUT/plots-w{w}/force_approach.png, area_approach.png, and SVG) and the
# switch designer's table (contact resistance at 10 and 20 uN, opening force and work).
#   bash scripts/rough-vs-smooth-study.sh [OUT]     (default out/rough-vs-smooth)
#   W="3 6" bash scripts/rough-vs-smooth-study.sh   (a subset of w)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out/rough-vs-smooth}
W=${W:-"1 3 6"}
cargo build --release --quiet
STICTION=./target/release/stiction
mkdir -p "$OUT"
for w in $W; do
  start=$(date +%s)
  $STICTION run "cases/ru-rough-sphere/rough-w$w.toml" --set 'sweep.values=[2.0]' --out "$OUT/rough-w$w" \
    --overwrite --quiet
  for law in lj cohesive; do
    $STICTION run "cases/ru-sphere/smooth-$law-w$w.toml" --out "$OUT/smooth-$law-w$w" --overwrite --quiet
  done
  # the plot labels each run by its folder's name
  ln -sfn "rough-w$w/max_approach_nm=2" "$OUT/rough-w$w-2nm"
  $STICTION plot "$OUT/rough-w$w-2nm" "$OUT/smooth-lj-w$w" "$OUT/smooth-cohesive-w$w" \
    --output "$OUT/plots-w$w" --title "rough vs smooth, w = $w J/m^2"
  echo "w = $w: $(( $(date +%s) - start )) s"
done
runs=()
for w in $W; do runs+=("$OUT/rough-w$w-2nm" "$OUT/smooth-lj-w$w" "$OUT/smooth-cohesive-w$w"); done
python3 scripts/resistance_table.py "${runs[@]}" | tee "$OUT/table.md"
