"""Prints the numbers a switch designer quotes from run outputs (history.csv and summary.json):
per run the contact resistance at 10 and 20 uN on closing (loading, approach increasing) and on
opening (unloading), the resistance at the maximum force, the opening force (the pull-off force,
the largest tensile force the flat must overcome) and the opening work per cycle (cycles.csv).
Forces in the Ru cases' unit, nN; resistance in ohm. Interpolation: log R linear in force
between the two increments that bracket the force, on the first crossing of each branch.
Usage: python3 scripts/resistance_table.py RUN_DIR [RUN_DIR ...]"""
import csv
import json
import math
import os
import sys


def branches(rows):
    """(loading, unloading) rows of the first cycle, split at the maximum force."""
    peak = max(range(len(rows)), key=lambda i: float(rows[i]["force"]))
    return rows[: peak + 1], rows[peak:]


def resistance_at(rows, force, rising):
    for a, b in zip(rows, rows[1:]):
        fa, fb = float(a["force"]), float(b["force"])
        if (rising and fa <= force <= fb) or (not rising and fa >= force >= fb):
            ra, rb = float(a["contact_resistance"]), float(b["contact_resistance"])
            if not (math.isfinite(ra) and math.isfinite(rb)):
                return ra if math.isfinite(ra) else rb
            s = 1.0 if fb == fa else (force - fa) / (fb - fa)
            return math.exp(math.log(ra) + s * (math.log(rb) - math.log(ra)))
    return float("nan")


def main(runs):
    print("| run | R at 10 uN closing / opening (ohm) | R at 20 uN closing / opening (ohm) | R at max force (ohm) | max force (uN) | opening force (uN) | opening work per cycle (aJ) |")
    print("|---|---|---|---|---|---|---|")
    for run in runs:
        history = os.path.join(run, "history.csv")
        rows = list(csv.DictReader(open(history)))
        if "contact_resistance" not in rows[0]:
            print(f"| {run} | no contact_resistance column | | | | | |")
            continue
        loading, unloading = branches(rows)
        cells = []
        for f in (10e3, 20e3):
            closing = resistance_at(loading, f, True)
            opening = resistance_at(unloading, f, False)
            cells.append(f"{closing:.3f} / {opening:.3f}")
        s = json.load(open(os.path.join(run, "summary.json")))["interfaces"][0]
        cycles = list(csv.DictReader(open(os.path.join(run, "cycles.csv"))))
        work = " / ".join(f"{float(c['opening_work']):.0f}" for c in cycles)
        r_max = s["contact_resistance_at_max_force"]
        print(
            f"| {os.path.basename(os.path.dirname(run.rstrip('/'))) or run}/{os.path.basename(run.rstrip('/'))} | {cells[0]} | {cells[1]} | "
            f"{r_max:.3f} | {s['max_force'] / 1e3:.2f} | {-s['most_tensile_force'] / 1e3:.2f} | {work} |"
        )


if __name__ == "__main__":
    main(sys.argv[1:])
