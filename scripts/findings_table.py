"""Prints the numbers behind docs/ru-rough-sphere.md from run outputs (summary.json and
history.csv under out/): per run the maximum force and its approach, pull-off force and approach,
maximum real area, asperities in contact at maximum, the most compressed asperity's share of the
approach, the loading force at fixed approaches (to compare works of adhesion), the asperities
still attached at the end (a cold weld's count, from the run's warning) and the continuum's
plastic work over the flat's work on loading (t <= 1).
Usage: python3 scripts/findings_table.py [OUT_DIR]"""
import csv
import glob
import json
import os
import re
import sys

out = sys.argv[1] if len(sys.argv) > 1 else "out"


def loading_force(history, approach):
    rows = list(csv.DictReader(open(history)))
    best = None
    for r in rows:
        if float(r["time"]) > 1.0 + 1e-9:
            break
        if best is None or abs(float(r["approach"]) - approach) < abs(float(best["approach"]) - approach):
            best = r
    return float(best["force"]) if best else float("nan")


def area_at(history, approach, unloading):
    rows = [r for r in csv.DictReader(open(history)) if (float(r["time"]) > 1.0) == unloading]
    if not rows:
        return float("nan")
    r = min(rows, key=lambda r: abs(float(r["approach"]) - approach))
    return float(r["contact_area"])


print("| run | max force (uN) | at approach (nm) | pull-off (uN) | at approach (nm) | max real area (nm^2) | in contact at max | asperity share | F(1.0 nm) loading (uN) | area at 1.0 nm load / unload (nm^2) | contact lost at (nm) | attached at the end | continuum's share of the loading work |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for summary in sorted(glob.glob(os.path.join(out, "**", "summary.json"), recursive=True)):
    d = os.path.dirname(summary)
    s = json.load(open(summary))
    if not s.get("interfaces"):
        continue
    i = s["interfaces"][0]
    h = os.path.join(d, "history.csv")
    rows = list(csv.DictReader(open(h)))
    unload = [r for r in rows if float(r["time"]) > 1.0]
    attached = next((re.search(r"with (\d+) points in contact", w) for w in s["warnings"] if "had not separated" in w), None)
    attached = attached.group(1) if attached else "0"
    work, dissipated = 0.0, 0.0
    for a, b in zip(rows, rows[1:]):
        if float(b["time"]) <= 1.0 + 1e-9:
            work += 0.5 * (float(a["force"]) + float(b["force"])) * (float(b["approach"]) - float(a["approach"]))
            dissipated = float(b["plastic_dissipation"])
    share = f"{100 * dissipated / work:.0f}%" if work > 0 else "-"
    lost = next((float(r["approach"]) for r in unload if float(r["n_contact"]) == 0 and abs(float(r["force"])) < 1e-6), float("nan"))
    print(f"| {os.path.relpath(d, out)} | {i['max_force']/1e3:.2f} | {i['approach_at_max_force']:.2f} | {i['pull_off_force']/1e3:.2f} | "
          f"{i['approach_at_pull_off']:.3f} | {i['max_contact_area']:.0f} | {i['n_contact_at_max_force']:.0f} | "
          f"{i['point_share_of_approach_at_max_force']:.2f} | {loading_force(h, 1.0)/1e3:.2f} | "
          f"{area_at(h, 1.0, False):.0f} / {area_at(h, 1.0, True):.0f} | {lost:.3f} | {attached} | {share} |")
