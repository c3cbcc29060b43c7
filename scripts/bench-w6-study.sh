#!/usr/bin/env bash
# Benchmark (not a test): the w = 6 J/m^2 rough-sphere study with the paper's three maximum
# approaches (cases/ru-rough-sphere/rough-w6.toml, the shipped default: footprint compliance,
# no footprint limit), timed end to end after the build, and beside it the same study with
# point forces (each asperity's force at one surface point, no footprint), the cheapest model
# of the same roughness. The last line is the CPU-time ratio default / point forces.
#   bash scripts/bench-w6-study.sh [--set key=value ...]
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --workspace --quiet
point_case=cases/ru-rough-sphere/.bench-point-forces-w6.toml
trap 'rm -f "$point_case"' EXIT
sed '/^footprint_area/d; /^footprint_correction/d; 0,/^name = .*/s//name = "rough-w6-point-forces"/' \
  cases/ru-rough-sphere/rough-w6.toml >"$point_case"
for variant in default point-forces; do
  case=cases/ru-rough-sphere/rough-w6.toml
  [ "$variant" = point-forces ] && case=$point_case
  /usr/bin/time -f "%e %U %S" -o "out/bench-rough-w6-$variant.time" \
    ./target/release/stiction run "$case" --quiet --overwrite --out "out/bench-rough-w6-$variant" \
    --set output.vtk=false "$@"
done
python3 - <<'PY'
import json
cpu = {}
for variant in ["default", "point-forces"]:
    wall, user, system = map(float, open(f"out/bench-rough-w6-{variant}.time").read().split())
    cpu[variant] = user + system
    for r in json.load(open(f"out/bench-rough-w6-{variant}/sweep.json")):
        print(f"{variant} {r['output_directory']}: {r['increments']} increments ({r['cut_increments']} cut, "
              f"{r['snaps']} snaps), {r['newton_iterations']} iterations, {r['factorizations']} factorizations, "
              f"{r['wall_seconds']:.1f} s (discarded attempts {r['discarded_attempt_seconds']:.1f})")
    print(f"{variant}: {wall:.1f} s wall, {user + system:.1f} s CPU for the study")
print(f"default/point-forces CPU time ratio {cpu['default'] / cpu['point-forces']:.2f}")
PY
