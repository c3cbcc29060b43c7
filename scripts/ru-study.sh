#!/usr/bin/env bash
# The Ru rough-sphere study behind docs/ru-rough-sphere.md (a long run, not a test), and the
# tables and figures of that page regenerated from it:
# - the shipped default: rough-w{1,3,6}.toml, each at the paper's three maximum approaches
#   (footprint compliance, no footprint limit);
# - sensitivity, a bulk footprint limit: the same with limit_pressure = "von-mises-disc"
#   (rough-w6-bulk-limit.toml at w = 6), at 2.0 nm;
# - sensitivity, point forces: each asperity's force at one surface point (no footprint), at
#   2.0 nm;
# - the smooth elastic-plastic Lennard-Jones sphere at w = 1 (cases/ru-sphere/smooth-lj-w1.toml).
# The tables go into docs/ru-rough-sphere.md between its "generated" markers, the force and area
# plots of the w = 6 study into docs/figures/.
#   bash scripts/ru-study.sh [OUT]     (default out/ru-study)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out/ru-study}
cargo build --release --quiet
S=./target/release/stiction
CASES=cases/ru-rough-sphere
mkdir -p "$OUT"
run() { # folder, case, extra arguments
  local folder=$1 case=$2
  shift 2
  local start
  start=$(date +%s)
  mkdir -p "$(dirname "$OUT/$folder")"
  $S run "$case" --out "$OUT/$folder" --overwrite --quiet --set output.vtk=false "$@" >"$OUT/$folder.log" 2>&1 ||
    { echo "$folder failed: see $OUT/$folder.log"; exit 1; }
  echo "$folder: $(($(date +%s) - start)) s"
}
for w in 1 3 6; do
  run "default/rough-w$w" "$CASES/rough-w$w.toml"
  run "bulk-limit/rough-w$w" "$CASES/rough-w$w.toml" --set 'sweep.values=[2.0]' \
    --set 'interfaces.0.points.footprint_correction={ limit_pressure = "von-mises-disc" }'
  # point forces: the case without its footprint (a copy beside it, for its relative paths)
  point_case="$CASES/.point-forces-w$w.toml"
  trap 'rm -f "$point_case"' EXIT
  sed '/^footprint_area/d; /^footprint_correction/d' "$CASES/rough-w$w.toml" >"$point_case"
  run "point-forces/rough-w$w" "$point_case" --set 'sweep.values=[2.0]'
  rm -f "$point_case"
done
run "smooth/smooth-lj-w1" cases/ru-sphere/smooth-lj-w1.toml
for part in default bulk-limit point-forces; do
  python3 scripts/findings_table.py "$OUT/$part" >"$OUT/$part.md"
done
cp "$OUT/default/rough-w6/combined_force_approach.png" docs/figures/rough-w6-force.png
cp "$OUT/default/rough-w6/combined_area_approach.png" docs/figures/rough-w6-area.png
python3 - "$OUT" docs/ru-rough-sphere.md <<'PY'
import re
import sys

out, doc = sys.argv[1], sys.argv[2]
text = open(doc).read()
for part in ["default", "bulk-limit", "point-forces"]:
    table = open(f"{out}/{part}.md").read().strip()
    begin, end = f"<!-- generated: {part} (scripts/ru-study.sh) -->", f"<!-- end: {part} -->"
    pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
    if not pattern.search(text):
        sys.exit(f"{doc}: no markers for '{part}'")
    text = pattern.sub(lambda _: f"{begin}\n{table}\n{end}", text)
open(doc, "w").write(text)
PY
echo "tables written into docs/ru-rough-sphere.md; figures into docs/figures/"
