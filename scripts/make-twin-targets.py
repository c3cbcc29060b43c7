#!/usr/bin/env python3
"""Targets for a twin experiment of `stiction fit`: the force-approach curve (or, with
`--column contact_area`, the real-area curve) of a run of a case at known parameter values,
every other increment, and the same curve with Gaussian noise.

    python3 scripts/make-twin-targets.py RUN_FOLDER OUT.csv [--column force] [--noisy OUT_NOISY.csv --noise 0.01 --seed 3]

RUN_FOLDER holds the run's history.csv (made with the settings a fit's runs get: a fixed
solver.refactorization_cost_ratio and the same threads per run). The noisy file has a `sigma`
column: the noise's standard deviation, `--noise` times the rms of the measured force (an
instrument's noise, not a fraction of each value, which would give points near zero force an
arbitrarily small sigma).
"""
import argparse
import csv
import math
import random
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("out")
    ap.add_argument("--noisy")
    ap.add_argument("--noise", type=float, default=0.01)
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--column", default="force", help="the history.csv column: force or contact_area")
    ap.add_argument("--header", default="", help="comment lines for the files' top ('\\n' separated)")
    a = ap.parse_args()
    rows = list(csv.DictReader(open(f"{a.run}/history.csv")))
    if not rows:
        sys.exit(f"{a.run}/history.csv has no rows")
    top = max(range(len(rows)), key=lambda i: float(rows[i]["approach"]))
    points = [
        (float(r["approach"]), float(r[a.column]), "loading" if i <= top else "unloading")
        for i, r in enumerate(rows)
        if i > 0 and i % 2 == 0
    ]
    header = [f"# {line}" for line in a.header.split("\\n") if line]
    with open(a.out, "w") as f:
        f.write("\n".join(header + [f"approach,{a.column},branch"]) + "\n")
        for x, y, b in points:
            f.write(f"{x:.6g},{y:.10g},{b}\n")
    if a.noisy:
        rng = random.Random(a.seed)
        sigma = a.noise * math.sqrt(sum(y * y for _, y, _ in points) / len(points))
        with open(a.noisy, "w") as f:
            note = [f"# with Gaussian noise of sigma = {a.noise} x rms {a.column} = {sigma:.6g} (seed {a.seed})"]
            f.write("\n".join(header + note + [f"approach,{a.column},branch,sigma"]) + "\n")
            for x, y, b in points:
                f.write(f"{x:.6g},{y + rng.gauss(0.0, sigma):.10g},{b},{sigma:.6g}\n")


if __name__ == "__main__":
    main()
