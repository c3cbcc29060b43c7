#!/usr/bin/env bash
# Regenerates the validation report, docs/validation-report.md: runs the validation tests with
# STICTION_VALIDATION_RECORD set (each `stiction_tests::validate` call appends its comparison:
# quantity, measured, reference and its source, tolerance) and tabulates what they recorded
# (scripts/validation_table.py). About 20 minutes on 2 cores.
#   bash scripts/validation-report.sh                      # every validation test
#   bash scripts/validation-report.sh -- --include-ignored # and the long ones run by hand
#   REPORT=/tmp/r.md bash scripts/validation-report.sh -- hertz::   # a module, elsewhere
# Failed comparisons are in the table too (marked); the script then exits with the tests' status.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-gmsh.sh
report="${REPORT:-docs/validation-report.md}"
if [ "${1:-}" = "--" ]; then shift; fi
record="$(mktemp)"
trap 'rm -f "$record"' EXIT
status=0
STICTION_VALIDATION_RECORD="$record" cargo test -p stiction-tests --test validation -- "$@" || status=$?
python3 scripts/validation_table.py "$record" > "$report.tmp"
mv "$report.tmp" "$report"
echo "wrote $report: $(grep "comparisons in" "$report")"
exit "$status"
