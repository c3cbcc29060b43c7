#!/usr/bin/env bash
# Benchmark (not a test): the w = 6 J/m^2 rough-sphere study with the paper's three maximum
# approaches (cases/ru-rough-sphere/rough-w6.toml), timed end to end after the build.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --workspace --quiet
start=$(date +%s.%N)
./target/release/stiction run cases/ru-rough-sphere/rough-w6.toml --quiet --overwrite --out out/bench-rough-w6 "$@"
end=$(date +%s.%N)
python3 - "$start" "$end" <<'PY'
import json, sys, glob
wall = float(sys.argv[2]) - float(sys.argv[1])
runs = json.load(open("out/bench-rough-w6/sweep.json"))
for r in runs:
    print(f"{r['output_directory']}: {r['increments']} increments, {r['newton_iterations']} Newton iterations, "
          f"{r['n_free_dofs']} free dofs, {r['wall_seconds']:.1f} s (assembly {r['assembly_seconds']:.1f}, "
          f"factorization {r['factorization_seconds']:.1f}, solve {r['solve_seconds']:.1f})")
print(f"total wall time {wall:.1f} s for {len(runs)} runs")
PY
