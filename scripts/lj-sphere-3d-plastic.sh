#!/usr/bin/env bash
# The elastic-perfectly plastic Lennard-Jones sphere in 3D (a long run, not a test): the quarter
# of cases/validation/lj-sphere-3d.toml with von Mises plasticity (Y = 3.42 GPa) and the cycle and
# solver settings of its axisymmetric twin cases/ru-sphere/smooth-lj-w{W}.toml (w = 3 and 6: loaded
# to 2 nm, unloaded to -3 nm, folds crossed by snaps, refactorization cost ratio 20; w = 1: back
# to -1 nm, folds crossed by arc length), on one of two meshes:
#   4nm: h_contact = 4 nm, layer = 8 nm, r_fine = 30 nm (11,872 free dofs; 21 min for the w = 3
#        cycle and 28 min for w = 6 on one thread)
#   2nm: the shipped h_contact = 2 nm with r_fine = 65 nm (79,716 free dofs; many hours: run it
#        in sittings, each ended by Ctrl-C or `--stop-after`, and go on with --resume)
#   bash scripts/lj-sphere-3d-plastic.sh W MESH OUT [more `stiction run` arguments]
# e.g. bash scripts/lj-sphere-3d-plastic.sh 6 2nm out/lj3d-2nm-w6 --set solver.threads=1
#      bash scripts/lj-sphere-3d-plastic.sh 6 2nm out/lj3d-2nm-w6 --resume
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 W MESH OUT [stiction run arguments]   (W in J/m^2: 1, 3 or 6; MESH: 4nm or 2nm)" >&2
  exit 2
fi
W=$1 MESH=$2 OUT=$3
shift 3
case "$W" in
  1|3|6) ;;
  *) echo "$0: W must be 1, 3 or 6 (the works of adhesion of cases/ru-sphere/smooth-lj-w*.toml), got '$W'" >&2; exit 2 ;;
esac
case "$MESH" in
  4nm) mesh=(--set mesh.parameters.h_contact=4.0 --set mesh.parameters.layer=8.0 --set mesh.parameters.r_fine=30.0) ;;
  2nm) mesh=(--set mesh.parameters.r_fine=65.0) ;;
  *) echo "$0: MESH must be 4nm or 2nm, got '$MESH'" >&2; exit 2 ;;
esac
cd "$(dirname "$0")/.."
source scripts/ensure-gmsh.sh
cargo build --release --quiet
# the twin's cycle and solver settings, read from the case (and its base) so that the two stay
# the same: the base's cycle and continuation, then the case's `set` list
twin="cases/ru-sphere/smooth-lj-w$W.toml"
sets=()
while IFS= read -r s; do sets+=(--set "$s"); done < <(python3 - "$twin" <<'EOF'
import json, os, sys, tomllib
path = sys.argv[1]
case = tomllib.load(open(path, "rb"))
base = case
if "base" in case:
    base = tomllib.load(open(os.path.join(os.path.dirname(path), case["base"]), "rb"))
print("amplitudes.cycle.value=" + json.dumps(base["amplitudes"]["cycle"]["value"]))
print("solver.continuation=" + json.dumps(base["solver"]["continuation"]))
for s in case.get("set", []):
    print(s)
EOF
)
exec ./target/release/stiction run cases/validation/lj-sphere-3d.toml --out "$OUT" --quiet \
  --set output.vtk=false "${mesh[@]}" --set "interfaces.0.parameters.w=$W.0" "${sets[@]}" \
  --set 'materials.ru.model="j2-plasticity"' --set materials.ru.yield_stress=3.42 "$@"
