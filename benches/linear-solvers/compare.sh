#!/usr/bin/env bash
# The linear-algebra limit: the tangent of the CalculiX benchmark (99,945 equations, at its last
# state, 2.5 nm into the plastic hemisphere with its 8,663 springs) factored and solved by faer
# as Stiction uses it, by CHOLMOD and by MUMPS, each in its own process on the same threads:
#   bash benches/linear-solvers/compare.sh [OUT] [--matrix FILE.mtx] [--threads N] [--repeats N]
# Exports the matrix (a run of benches/calculix-hemisphere/case.toml, about a minute) unless
# --matrix names a symmetric Matrix Market file; installs SuiteSparse and sequential MUMPS from
# Debian's packages when missing and builds the two small C drivers beside this script. Each
# solver reads the file, analyses once, factors REPEATS times (the best time counts) and solves
# A x = b with b = A 1; the table gives times, factor entries, the relative residual and the
# peak memory of the process. Threads: rayon's for faer (which factors a factor below 50M
# entries on one of them, as a run does), OpenBLAS's for CHOLMOD and MUMPS (sequential MUMPS,
# whose parallelism is the BLAS's); CHOLMOD and MUMPS also run on one thread. The last line reads
# `faer/best factorization time ratio R`: Stiction's default factorization (METIS nested
# dissection, single-precision factor refined to double) against the fastest of all the others.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
out="$root/out/linear-solvers"
matrix=""
threads=2
repeats=3
while [ $# -gt 0 ]; do
  case "$1" in
    --matrix) matrix="$(realpath "$2")"; shift ;;
    --threads) threads="$2"; shift ;;
    --repeats) repeats="$2"; shift ;;
    -*) echo "unknown option $1 (expected --matrix, --threads, --repeats)" >&2; exit 2 ;;
    *) out="$1" ;;
  esac
  shift
done
mkdir -p "$out"
out="$(realpath "$out")"
cd "$root"

if [ ! -f /usr/include/suitesparse/cholmod.h ] || [ ! -f /usr/include/dmumps_c.h ] || [ ! -e /usr/lib/x86_64-linux-gnu/libdmumps_seq.so ]; then
  SUDO=""
  if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
  echo "installing SuiteSparse and sequential MUMPS (Debian packages libsuitesparse-dev, libmumps-seq-dev)..." >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    libsuitesparse-dev libmumps-seq-dev libopenblas-dev gcc >/dev/null
fi
gcc -O2 -Wall -o "$out/cholmod_driver" "$here/cholmod_driver.c" -lcholmod -lm
for p in d s; do
  flag=""
  if [ "$p" = s ]; then flag=-DSINGLE; fi
  gcc -O2 -Wall $flag -I/usr/include/mumps_seq -o "$out/mumps_driver_$p" "$here/mumps_driver.c" \
    -l${p}mumps_seq -lmumps_common_seq -lmpiseq_seq -lpord_seq -lm
done
cargo build --release --workspace >&2
faer="$(cargo bench --no-run --bench linear_solvers --message-format=json 2>"$out/bench-build.log" \
  | python3 -c 'import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m["target"]["name"] == "linear_solvers" and m.get("executable"):
        print(m["executable"])')"
[ -x "$faer" ] || { cat "$out/bench-build.log" >&2; echo "the faer driver did not build" >&2; exit 1; }

if [ -z "$matrix" ]; then
  source scripts/ensure-gmsh.sh
  "$faer" export benches/calculix-hemisphere/case.toml "$out" >&2
  matrix="$out/tangent.mtx"
fi

results="$out/results.jsonl"
: > "$results"
measure() { # label, threads, command...
  local label=$1 n=$2; shift 2
  echo "  $label" >&2
  RAYON_NUM_THREADS="$n" OPENBLAS_NUM_THREADS="$n" OMP_NUM_THREADS="$n" "$@" \
    | sed "s/^{/{\"label\": \"$label\", \"threads\": $n, /" >> "$results" || { echo "$label failed" >&2; exit 1; }
}
echo "factoring $matrix on $threads threads, best of $repeats:" >&2
t=$threads
measure "faer, default (nd, single)" "$t" "$faer" factor "$matrix" nd single "$repeats"
measure "faer, nd, double" "$t" "$faer" factor "$matrix" nd double "$repeats"
measure "faer, amd, double" "$t" "$faer" factor "$matrix" amd double "$repeats"
measure "CHOLMOD, its own choice" "$t" "$out/cholmod_driver" "$matrix" default "$repeats"
measure "CHOLMOD, its own choice" 1 "$out/cholmod_driver" "$matrix" default "$repeats"
measure "CHOLMOD, amd" "$t" "$out/cholmod_driver" "$matrix" amd "$repeats"
measure "MUMPS, its own choice, double" "$t" "$out/mumps_driver_d" "$matrix" auto "$repeats"
measure "MUMPS, pord, double" "$t" "$out/mumps_driver_d" "$matrix" pord "$repeats"
measure "MUMPS, its own choice, single" "$t" "$out/mumps_driver_s" "$matrix" auto "$repeats"
measure "MUMPS, its own choice, single" 1 "$out/mumps_driver_s" "$matrix" auto "$repeats"

python3 - "$results" <<'PY'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
print(f"{rows[0]['equations']} equations; threads: those the factorization used; times in s (factorization: best of the repeats), memory in MB")
head = ("solver", "threads", "ordering", "precision", "analyse", "factorize", "solve", "factor entries", "residual", "peak RSS")
# faer's factor_threads: what Stiction uses of the threads it is given (one below a factor size)
table = [head] + [
    (r["label"], str(r.get("factor_threads", r["threads"])), r["ordering"], r["precision"], f"{r['analyse_s']:.2f}", f"{r['factorize_s']:.2f}",
     f"{r['solve_s']:.3f}", f"{r['factor_entries'] / 1e6:.1f}M", f"{r['residual']:.1e}", f"{r['peak_rss_mb']:.0f}")
    for r in rows
]
widths = [max(len(row[i]) for row in table) for i in range(len(head))]
for row in table:
    print("  ".join(cell.ljust(w) for cell, w in zip(row, widths)))
faer = rows[0]
others = [r for r in rows if r["solver"] != "faer"]
best = min(others, key=lambda r: r["factorize_s"])
double = [r for r in others if r["precision"] == "Double"]
best_double = min(double, key=lambda r: r["factorize_s"])
faer_double = min((r for r in rows if r["solver"] == "faer" and r["precision"] == "Double"), key=lambda r: r["factorize_s"])
print(f"double precision: faer {faer_double['factorize_s']:.2f} s against {best_double['label']} "
      f"{best_double['factorize_s']:.2f} s, ratio {faer_double['factorize_s'] / best_double['factorize_s']:.2f}")
print(f"best of the others: {best['label']}, {best['factorize_s']:.2f} s")
print(f"faer/best factorization time ratio {faer['factorize_s'] / best['factorize_s']:.2f}")
PY
