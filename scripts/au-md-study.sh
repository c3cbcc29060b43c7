#!/usr/bin/env bash
# The two-scale study with gold asperities from molecular dynamics, at three works of adhesion:
# for each W (1, the potential's own 1.83, and 3 J/m^2; the paper's 6 is beyond what scaling the
# gold potential's cross interaction reaches), the nano-asperity experiment with the interface
# scaled to W (`stiction md`, [adhesion] work_of_adhesion), its table fitted (6th-order
# loading, 7th-order unloading), and the rough gold hemisphere (cases/md/au-rough-sphere.toml)
# run with that calibration; then the force and area curves of the three overlaid (OUT/plots,
# copied to docs/figures/md/) and a table of the results (OUT/results.md, written into
# docs/md.md between its markers for the size).
#   SIZE=quick: the quick asperity (cases/md/au-asperity-quick.toml, 1.0 nm high), the
#     hemisphere pressed to 0.8 nm; about 7 minutes on 2 cores (the default);
#   SIZE=paper: the paper's asperity, speed and maxima (cases/md/au-asperity-paper.toml, 2.786 nm
#     high, 7 m/s, maxima 0.5 to 2.0 nm), the hemisphere pressed to 2.0 nm; hours.
#   [SIZE=quick|paper] bash scripts/au-md-study.sh [OUT]     (default out/au-md-study-SIZE)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-lammps.sh
SIZE=${SIZE:-quick}
OUT=${1:-out/au-md-study-$SIZE}
case "$SIZE" in
  quick) MD=cases/md/au-asperity-quick.toml
         SPHERE=() ;;
  paper) MD=cases/md/au-asperity-paper.toml
         # the paper's asperity: 2.786 nm high on 9.566 nm^2; pressed to 2.0 nm
         SPHERE=(--set 'amplitudes.cycle.value=[-0.5, 2.0, -3.5]' --set interfaces.0.points.height=2.786
                 --set interfaces.0.points.footprint_area=9.566 --set interfaces.0.points.region_radius=117.6) ;;
  *) echo "SIZE must be quick or paper, got '$SIZE'" >&2; exit 2 ;;
esac
cargo build --release --quiet
S=./target/release/stiction
mkdir -p "$OUT"
echo "| W asked (J/m^2) | W measured (J/m^2) | cross scale | MD force range (nN) | max force (nN) | most tensile (nN) | separated | max real area (nm^2) |" >"$OUT/results.md"
echo "|---|---|---|---|---|---|---|---|" >>"$OUT/results.md"
runs=()
for W in 1.0 own 3.0; do
  name="w-$W"
  md="$OUT/$name.toml"
  cp "$MD" "$md"
  # the potential file is an absolute path in the shipped MD files, so the copy finds it
  if [ "$W" != own ]; then printf '\n[adhesion]\nwork_of_adhesion = %s\n' "$W" >>"$md"; fi
  start=$(date +%s)
  mkdir -p "$OUT/$name"
  $S md "$md" --out "$OUT/$name/md" | tee "$OUT/$name/md.log"
  $S calibrate "$OUT/$name/md/force-distance.csv" -o "$OUT/$name/calibration.toml" --loading-order 6 --unloading-order 7
  measured=$(sed -n 's/^# work_of_adhesion: //p' "$OUT/$name/md/force-distance.csv")
  $S run cases/md/au-rough-sphere.toml --out "$OUT/spheres/$name" --overwrite --quiet --set output.vtk=false \
    --set "interfaces.0.config_file=$(realpath "$OUT/$name/calibration.toml")" \
    --set "interfaces.0.parameters.expected_work_of_adhesion=$measured" "${SPHERE[@]}"
  python3 - "$OUT/$name" "$W" "$measured" >>"$OUT/results.md" <<'PY'
import json, re, sys
folder, asked, measured = sys.argv[1:]
md = open(f"{folder}/md/force-distance.csv").read()
scale = re.search(r"cross scale ([0-9.]+)", md).group(1)
forces = [float(l.split(",")[1]) for l in md.splitlines() if l and not l.startswith("#") and not l.startswith("distance")]
i = json.load(open(f"{folder}/../spheres/{folder.split('/')[-1]}/summary.json"))["interfaces"][0]
print(f"| {asked} | {float(measured):.3f} | {scale} | {min(forces):.1f} to {max(forces):.1f} | {i['max_force']:.1f} | "
      f"{i['most_tensile_force']:.1f} | {'yes' if i['separated'] else 'no'} | {i['max_contact_area']:.1f} |")
PY
  runs+=("$OUT/spheres/$name")
  echo "$name: $(($(date +%s) - start)) s"
done
$S plot "${runs[@]}" --output "$OUT/plots" --title "rough Au hemisphere, asperities from MD at three works of adhesion ($SIZE)"
cat "$OUT/results.md"
# the table into docs/md.md between its markers for this size, the plots into docs/figures/md/
mkdir -p docs/figures/md
cp "$OUT/plots/force_approach.png" "docs/figures/md/au-study-$SIZE-force.png"
cp "$OUT/plots/area_approach.png" "docs/figures/md/au-study-$SIZE-area.png"
python3 - "$OUT/results.md" docs/md.md "$SIZE" <<'PY'
import re
import sys

table, doc, size = open(sys.argv[1]).read().strip(), sys.argv[2], sys.argv[3]
text = open(doc).read()
begin, end = f"<!-- generated: au-md-study-{size} (scripts/au-md-study.sh) -->", f"<!-- end: au-md-study-{size} -->"
pattern = re.compile(re.escape(begin) + ".*?" + re.escape(end), re.S)
if not pattern.search(text):
    sys.exit(f"{doc}: no markers for 'au-md-study-{size}'")
open(doc, "w").write(pattern.sub(lambda _: f"{begin}\n{table}\n{end}", text))
PY
echo "table written into docs/md.md; plots into docs/figures/md/"
