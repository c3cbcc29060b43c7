#!/usr/bin/env bash
# Mesh convergence of the rough Ru hemisphere (w = 6 J/m^2 surrogate, maximum approach 2.0 nm,
# then unloading to -2.5 nm; footprint 12.2 nm^2 per asperity): the quick case at contact mesh
# sizes h_contact = 20 (the quick default), 10, 7 and 5 nm (or those in $H); below 20 nm the
# refinement is a surface layer (`layer` nm thick, r_fine = 120 nm around the pole) so the ball
# under the contact stays coarse. Faces of the 5 nm mesh (~11 nm^2) are no larger than the
# footprint.
# The runs carry the footprint correction (`points.footprint_correction`: each asperity in
# series with its footprint's compliance, which the mesh does not resolve), as the shipped
# cases do. --uncorrected adds the runs without it (footprints only; their
# unloading stops at -0.25 nm, past the pull-off, because on the finer meshes the separation of
# the last asperities crawls), --point the runs with point forces.
# Prints per resolution: free dofs, maximum force, most tensile force, maximum real
# area, plastic dissipation (the continuum's and the footprints' sliders'), largest equivalent
# plastic strain, run time, and the change from the previous resolution.
# Usage: [H="20 10 7 5"] bash scripts/mesh-convergence.sh [OUT_DIR] [--uncorrected] [--point]
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/mesh-convergence
point=0
uncorrected=0
for arg in "$@"; do
  case "$arg" in
    --point) point=1 ;;
    --uncorrected) uncorrected=1 ;;
    *) out=$arg ;;
  esac
done
source scripts/ensure-gmsh.sh
cargo build --release --workspace >&2
mkdir -p "$out"

run() { # label, footprint area, mesh --set arguments
  local label=$1 area=$2; shift 2
  local points="interfaces.0.points.footprint_area=$area"
  [ "${label%%-*}" = corrected ] || points="interfaces.0.points={ density = 0.0079, region_radius = 117.6, min_spacing = 3.5, height = 2.786, seed = 1, footprint_area = $area }"
  [ "${label%%-*}" = corrected ] || set -- --set steps.1.end_time=1.5 "$@"
  ./target/release/stiction run cases/ru-rough-sphere/rough-w6-quick.toml --quiet --overwrite \
    --out "$out/$label" --set "$points" --set output.vtk=false "$@" \
    > "$out/$label.log" 2>&1 \
    || { cat "$out/$label.log" >&2; exit 1; }
}
layer=(--set mesh.parameters.r_fine=120.0 --set mesh.parameters.layer=10.0 --set mesh.parameters.growth=0.5)
labels=()
for h in ${H:-20 10 7 5}; do
  if [ "$h" = 20 ]; then mesh=(); else mesh=(--set "mesh.parameters.h_contact=$h" "${layer[@]}"); fi
  run "corrected-h$h" 12.2 ${mesh[@]+"${mesh[@]}"}
  labels+=("corrected-h$h")
  if [ "$uncorrected" = 1 ]; then
    run "footprint-h$h" 12.2 ${mesh[@]+"${mesh[@]}"}
    labels+=("footprint-h$h")
  fi
  if [ "$point" = 1 ]; then
    run "point-h$h" 0.0 ${mesh[@]+"${mesh[@]}"}
    labels+=("point-h$h")
  fi
done

python3 - "$out" "${labels[@]}" <<'EOF'
import json, sys
out, labels = sys.argv[1], sys.argv[2:]
print("| run | free dofs | max force (uN) | pull-off (uN) | max real area (nm^2) | plastic dissipation (aJ) | max eq. plastic strain | run time (s) | change from previous: force / pull-off / area |")
print("|---|---|---|---|---|---|---|---|---|")
previous = {}
for label in labels:
    s = json.load(open(f"{out}/{label}/summary.json"))
    i = s["interfaces"][0]
    row = (i["max_force"], i["most_tensile_force"], i["max_contact_area"])
    kind = label.split("-")[0]
    change = ""
    if kind in previous:
        change = " / ".join(f"{100 * (a / b - 1):+.2f}%" for a, b in zip(row, previous[kind]))
    previous[kind] = row
    eps = s.get("max_equivalent_plastic_strain")
    print(f"| {label} | {s['n_free_dofs']} | {row[0] / 1e3:.3f} | {row[1] / 1e3:.3f} | {row[2]:.1f} | "
          f"{s['plastic_dissipation']:.1f} | {eps if eps is None else f'{eps:.4f}'} | {s['wall_seconds']:.1f} | {change} |")
EOF
grep -h "^warning" "$out"/*.log | sort -u || true
