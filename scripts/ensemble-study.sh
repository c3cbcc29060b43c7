#!/usr/bin/env bash
# The ensemble study (a long run, not a test): the w = 6 J/m^2 rough sphere pressed to 2.0 nm
# over 16 asperity layouts on the study mesh (cases/ru-rough-sphere/ensemble-w6.toml), then the
# density sweep: 16 layouts on the quick mesh at each of three asperity densities. Prints the
# mean and 95% confidence interval of the maximum and pull-off forces. Re-running resumes.
#   bash scripts/ensemble-study.sh [OUT]          (default out/ensemble-study)
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-out/ensemble-study}
DENSITIES=${DENSITIES:-"0.005 0.0079 0.011"}
cargo build --release --quiet
STICTION=./target/release/stiction
start=$(date +%s)
$STICTION ensemble cases/ru-rough-sphere/ensemble-w6.toml --out "$OUT/w6-study-mesh" --quiet > /dev/null
for d in $DENSITIES; do
  $STICTION ensemble cases/ru-rough-sphere/ensemble-quick.toml --out "$OUT/density-$d" --quiet \
    --set ensemble.members=16 --set interfaces.0.points.density=$d > /dev/null
done
echo "wall time $(( $(date +%s) - start )) s"
python3 - "$OUT" <<'PY'
import json, sys, glob, os
print("| ensemble | members | asperities in contact at max | max force (uN) | pull-off (uN) | max real area (nm^2) |")
print("|---|---|---|---|---|---|")
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*", "ensemble.json"))):
    e = json.load(open(path))
    s = {q["quantity"].split(".")[-1]: q for q in e["statistics"]}
    def show(q, scale=1.0, digits=2):
        x = s[q]
        return f"{x['mean'] * scale:.{digits}f} +- {x['ci95_half_width'] * scale:.{digits}f}"
    print(f"| {os.path.basename(os.path.dirname(path))} | {e['completed']}/{e['members']} | "
          f"{show('n_contact_at_max_force', 1, 1)} | {show('max_force', 1e-3)} | {show('most_tensile_force', 1e-3)} | "
          f"{show('max_contact_area', 1, 0)} |")
PY
