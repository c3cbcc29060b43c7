"""Prints the table behind docs/ru-rough-sphere.md from run outputs (summary.json and
history.csv under a folder): per run the maximum force and its approach, the pull-off (only when
the sphere separated; otherwise the most tensile force, marked "not separated"), the maximum
real area, asperities in contact at the maximum, the most compressed asperity's share of the
approach, the loading force at 1.0 nm (to compare works of adhesion), the real area at 1.0 nm
on loading and unloading, the approach after which no asperity is in contact, the asperities
still attached at the end, and the plastic work (continuum and any footprint sliders) over the
flat's work on loading (t <= 1). Forces in uN, lengths in nm, areas in nm^2.
Usage: python3 scripts/findings_table.py [OUT_DIR]"""
import csv
import glob
import json
import os
import re
import sys

out = sys.argv[1] if len(sys.argv) > 1 else "out"


def loading_force(rows, approach):
    loading = [r for r in rows if float(r["time"]) <= 1.0 + 1e-9]
    best = min(loading, key=lambda r: abs(float(r["approach"]) - approach))
    return float(best["force"])


def area_at(rows, approach, unloading):
    part = [r for r in rows if (float(r["time"]) > 1.0) == unloading]
    if not part:
        return float("nan")
    return float(min(part, key=lambda r: abs(float(r["approach"]) - approach))["contact_area"])


print("| run | max force (uN) | at (nm) | pull-off (uN) | at (nm) | max real area (nm^2) | in contact at max | asperity share of the approach | F(1.0 nm) loading (uN) | area at 1.0 nm, load / unload (nm^2) | no contact after (nm) | attached at the end | plastic work / loading work |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
def natural(path):
    """Sort key: numbers (a sweep's values) by value."""
    return [(0, float(x), "") if re.fullmatch(r"[0-9.]+", x) else (1, 0.0, x) for x in re.split(r"[=/]", path)]


for summary in sorted(glob.glob(os.path.join(out, "**", "summary.json"), recursive=True), key=natural):
    d = os.path.dirname(summary)
    s = json.load(open(summary))
    if not s.get("interfaces") or s["status"] != "completed":
        continue
    i = s["interfaces"][0]
    rows = list(csv.DictReader(open(os.path.join(d, "history.csv"))))
    work, dissipated = 0.0, 0.0
    for a, b in zip(rows, rows[1:]):
        if float(b["time"]) <= 1.0 + 1e-9:
            work += 0.5 * (float(a["force"]) + float(b["force"])) * (float(b["approach"]) - float(a["approach"]))
            dissipated = float(b["plastic_dissipation"])
    share = f"{100 * dissipated / work:.1f}%" if work > 0 else "-"
    in_contact = [r for r in rows if float(r["time"]) > 1.0 and float(r["n_contact"]) > 0]
    lost = f"{float(in_contact[-1]['approach']):.3f}" if i["separated"] and in_contact else "-"
    if i["separated"]:
        pull_off = f"{i['pull_off_force'] / 1e3:.2f}"
    else:
        pull_off = f"not separated (most tensile {i['most_tensile_force'] / 1e3:.2f})"
    print(f"| {os.path.relpath(d, out)} | {i['max_force'] / 1e3:.2f} | {i['approach_at_max_force']:.2f} | {pull_off} | "
          f"{i['approach_at_most_tensile_force']:.3f} | {i['max_contact_area']:.0f} | {i['n_contact_at_max_force']:.0f} | "
          f"{i['point_share_of_approach_at_max_force']:.2f} | {loading_force(rows, 1.0) / 1e3:.2f} | "
          f"{area_at(rows, 1.0, False):.0f} / {area_at(rows, 1.0, True):.0f} | {lost} | {i['final_n_contact']} | {share} |")
