#!/usr/bin/env bash
# The cold-weld plateau of the smooth elastic-perfectly plastic Lennard-Jones sphere against the
# largest approach of its cycle: `cases/ru-sphere/smooth-lj-w$W.toml` (axisymmetric) with the
# contact mesh `h_contact` = $H nm within 40 nm of the pole, loaded to each approach in $PEAKS
# and unloaded to -3 nm (one thread per run).
# On loading, the bonded region grows in folds (the path has no nearby equilibrium; the run
# snaps along the damped flow), each adding plastic dissipation; the load the drawn-out neck
# carries on unloading is set by the bonded region reached, so it is a staircase in the peak
# approach, flat between folds. A cycle whose peak lies at a fold can land on either step.
# Prints per peak: the snaps crossed while loading (their approaches), the plastic dissipation
# at the peak, the most tensile force (the plateau: the sphere is still drawn out at -3 nm) and
# the plastic dissipation at the end; plots the force-approach curves in OUT_DIR/plots. A run
# that stops (the solver found no way on) is listed with the time it reached.
# Usage: [W=6] [H=4] [PEAKS="0.3 0.35 ..."] bash scripts/peak-approach-scan.sh [OUT_DIR [--set KEY=VALUE ...]]
# (the --set arguments go to every run, e.g. --set solver.tangent='"consistent"')
set -euo pipefail
cd "$(dirname "$0")/.."
w=${W:-6}
h=${H:-4}
peaks=${PEAKS:-0.3 0.35 0.4 0.45 0.5 0.55 0.6 0.65 0.7 0.75 0.8}
out=${1:-out/peak-approach-w$w-h$h}
shift || true
source scripts/ensure-gmsh.sh
cargo build --release --workspace >&2
mkdir -p "$out"
labels=()
for peak in $peaks; do
  label=peak-$peak
  ./target/release/stiction run "cases/ru-sphere/smooth-lj-w$w.toml" --quiet --overwrite --out "$out/$label" \
    --set output.vtk=false --set solver.threads=1 --set "mesh.parameters.h_contact=$h" \
    --set mesh.parameters.r_fine=40.0 --set "amplitudes.cycle.value=[0.0, $peak, -3.0]" "$@" \
    > "$out/$label.log" 2>&1 \
    || grep -q '"status": "failed"' "$out/$label/summary.json" 2>/dev/null \
    || { cat "$out/$label.log" >&2; exit 1; }
  labels+=("$label")
done
./target/release/stiction plot --title "smooth LJ sphere, w = $w, h = $h nm: cycles to each peak" \
  --output "$out/plots" "${labels[@]/#/$out/}" > /dev/null

python3 - "$out" "${labels[@]}" <<'EOF'
import csv, json, re, sys
out, labels = sys.argv[1], sys.argv[2:]
print("| peak approach (nm) | snaps while loading, at approach (nm) | plastic dissipation at the peak (aJ) | most tensile force (nN) | plastic dissipation at -3 nm (aJ) | run time (s) |")
print("|---|---|---|---|---|---|")
for label in labels:
    peak = float(label.split("-", 1)[1])
    s = json.load(open(f"{out}/{label}/summary.json"))
    rows = list(csv.DictReader(open(f"{out}/{label}/history.csv")))
    # the committed state at the end of loading (t = 1)
    at_peak = [r for r in rows if float(r["time"]) <= 1.0 + 1e-12][-1]
    snapped = sorted({float(t) for t in re.findall(r"load: snapped at t = ([0-9.]+)", open(f"{out}/{label}/messages.log").read())})
    where = ", ".join(f"{peak * t:.3f}" for t in snapped)
    stopped = "" if s["status"] == "completed" else f" (stopped at t = {s['final_time']:.4f})"
    print(f"| {peak:g}{stopped} | {len(snapped)}: {where} | {float(at_peak['plastic_dissipation']):.0f} | "
          f"{min(float(r['force']) for r in rows):.0f} | {float(rows[-1]['plastic_dissipation']):.0f} | {s['wall_seconds']:.0f} |")
EOF
