#!/usr/bin/env bash
# Regenerates the shipped Au asperity calibration from molecular dynamics: runs the quick
# nano-asperity experiment (../au-asperity-quick.toml, about 80 s on 2 cores, with LAMMPS),
# keeps its table as au-quick.csv and fits au-quick.toml with `stiction calibrate`: 6th-order
# loading and 7th-order unloading polynomials (the paper's 4th and 5th orders miss the
# unloading's deepest pull, -100 nN, by 34 nN; these by 21 nN, in thermal noise of about 5 nN
# rms), with plots au-quick_force and au-quick_area. The MD folder goes to $OUT (default
# ../../../out/md-au-asperity-quick).
set -euo pipefail
cd "$(dirname "$0")"
STICTION=${STICTION:-../../../target/release/stiction}
OUT=${OUT:-../../../out/md-au-asperity-quick}
"$STICTION" md ../au-asperity-quick.toml --out "$OUT"
cp "$OUT/force-distance.csv" au-quick.csv
"$STICTION" calibrate au-quick.csv -o au-quick.toml --loading-order 6 --unloading-order 7
