#!/usr/bin/env bash
# "From any start": the smooth spheres of `cases/ru-sphere/` (Lennard-Jones and cohesive zone,
# each work of adhesion in $WS) run from several initial gaps, elastic and elastic-perfectly
# plastic, on the contact mesh `h_contact` = $H nm within 40 nm of the pole (one thread per run,
# $JOBS runs at a time). The Lennard-Jones gaps ($LJ_GAPS) include starts inside the jump-in range
# (the shipped 3 z0 = 0.507 nm at w = 3 and 6) and one far outside it; the cohesive-zone gaps
# ($CZ_GAPS) the pole in touch and two starts apart (a point bonds when it first touches). Each
# cycle is the case's own (approach 0 -> 2 -> -3 nm past the start).
# DIM=3d runs the same cycles on the 3D quarter (`cases/validation/lj-sphere-3d.toml` and
# `cohesive-sphere-3d.toml` with each case's own `set` list: its w, cycle and solver settings;
# 10-node tets, `h_contact` = $H nm, default 8, within 40 nm of the pole and 2 $H under the
# surface); its forces are printed for the whole sphere (4 x the quarter's).
# Prints per run: the status and the time reached, snaps, limit points, cut increments, the
# largest force, the most tensile force while unloading (for an elastic body with a reversible
# law, the pull-off: one equilibrium branch whatever the start) and whether the flat had
# separated. A run that stops is listed with the reason.
# Usage: [DIM=axisymmetric|3d] [WS="3 6"] [H=4 (3d: 8)] [JOBS=2] [LJ_GAPS=..] [CZ_GAPS=..]
#        bash scripts/start-gap-scan.sh [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
ws=${WS:-3 6}
dim=${DIM:-axisymmetric}
case "$dim" in
  axisymmetric) h=${H:-4} ;;
  3d) h=${H:-8} ;;
  *) echo "DIM must be axisymmetric or 3d, not '$dim'" >&2; exit 2 ;;
esac
lj_gaps=${LJ_GAPS:-0.25 0.507 1.5}
cz_gaps=${CZ_GAPS:-0 0.2 1.5}
out=${1:-out/start-gap-scan-$dim-h$h}
source scripts/ensure-gmsh.sh
cargo build --release --workspace >&2
mkdir -p "$out"

runs=()
for w in $ws; do
  for body in elastic plastic; do
    for gap in $lj_gaps; do runs+=("smooth-lj-w$w $body $gap"); done
    for gap in $cz_gaps; do runs+=("smooth-cohesive-w$w $body $gap"); done
  done
done

# one run: CASE BODY GAP (a run the solver stopped is a result; any other error ends the scan)
run_one() {
  local case=$1 body=$2 gap=$3 label="$1-$2-gap$3"
  local material=() file="cases/ru-sphere/$case.toml" model=()
  [ "$body" = elastic ] && material=(--set 'materials.ru.model="linear-elastic"')
  if [ "$dim" = 3d ]; then
    # the 3D quarter with the axisymmetric case's own settings (its `set` list)
    case "$case" in
      smooth-lj-*) file=cases/validation/lj-sphere-3d.toml ;;
      smooth-cohesive-*) file=cases/validation/cohesive-sphere-3d.toml ;;
    esac
    local sets
    sets=$(python3 -c 'import sys, tomllib; print("\n".join(tomllib.load(open(sys.argv[1], "rb"))["set"]))' \
      "cases/ru-sphere/$case.toml") \
      || { echo "DIM=3d takes each case's key 'set' (w = 3 and 6; read with Python 3.11 or later): cases/ru-sphere/$case.toml has none" >&2; return 255; }
    while IFS= read -r s; do model+=(--set "$s"); done <<< "$sets"
    model+=(--set "mesh.parameters.layer=$((2 * h))")
    [ "$body" = plastic ] && material=(--set 'materials.ru.model="j2-plasticity"' --set materials.ru.yield_stress=3.42)
  fi
  ./target/release/stiction run "$file" --quiet --overwrite --out "$out/$label" \
    --set output.vtk=false --set solver.threads=1 --set "mesh.parameters.h_contact=$h" \
    --set mesh.parameters.r_fine=40.0 --set "interfaces.0.initial_gap=$gap" "${model[@]}" "${material[@]}" \
    > "$out/$label.log" 2>&1 \
    || grep -q '"status": "failed"' "$out/$label/summary.json" 2>/dev/null \
    || { cat "$out/$label.log" >&2; return 255; }
}
export -f run_one
export out h dim
printf '%s\n' "${runs[@]}" | xargs -P "${JOBS:-2}" -L 1 bash -c 'run_one "$@"' _

python3 - "$out" "$dim" "${runs[@]}" <<'EOF'
import csv, json, sys
out, dim, runs = sys.argv[1], sys.argv[2], sys.argv[3:]
# the 3D quarter's forces are a quarter of the sphere's
scale = 4.0 if dim == "3d" else 1.0
print(f"{dim}; forces of the whole sphere")
print("| case | body | initial gap (nm) | status | snaps | limit points | cuts | max force (nN) | most tensile unloading (nN) | separated | run time (s) |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for run in runs:
    case, body, gap = run.split()
    d = f"{out}/{case}-{body}-gap{gap}"
    s = json.load(open(f"{d}/summary.json"))
    rows = list(csv.DictReader(open(f"{d}/history.csv")))
    unloading = [scale * float(r["force"]) for r in rows if float(r["time"]) > 1.0] or [float("nan")]
    status = "completed" if s["status"] == "completed" else f"stopped at t = {s['final_time']:.4f}: {s['message']}"
    attached = any("had not separated" in w for w in s["warnings"])
    print(f"| {case} | {body} | {gap} | {status} | {s['snaps']} | {s['limit_points']} | {s['cut_increments']} | "
          f"{max(scale * float(r['force']) for r in rows):.0f} | {min(unloading):.0f} | {'no' if attached else 'yes'} | {s['wall_seconds']:.0f} |")
EOF
