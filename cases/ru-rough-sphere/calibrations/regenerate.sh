#!/usr/bin/env bash
# Regenerates the shipped default asperity calibrations from the documented SURROGATE
# (plugins/ru-asperity/src/surrogate.rs): tables ru-surrogate-wW.csv, then fits
# ru-surrogate-wW.toml with `stiction calibrate` (4th-order loading, 5th-order unloading).
# These are NOT molecular-dynamics data; the reference paper's MD tables are not public.
set -euo pipefail
cd "$(dirname "$0")"
STICTION=${STICTION:-../../../target/release/stiction}
for w in 1 3 6; do
  "$STICTION" surrogate-table --work-of-adhesion "$w" -o "ru-surrogate-w$w.csv"
  "$STICTION" calibrate "ru-surrogate-w$w.csv" -o "ru-surrogate-w$w.toml"
done
