"""Renders a Stiction run's standard views to PNG with ParaView (pvbatch) and saves them as a
ParaView state to open and explore interactively (the views are built by `contact_views.py`,
beside this script; any run: axisymmetric, 2D or 3D, a sphere, a block, a beam):
- view_von_mises.png, view_equivalent_plastic_strain.png (if the material has it): the field on
  a section through the contact region, zoomed on it;
- view_contact.png (if the run has interface points): the contact region seen from the flat (3D)
  or from the side (2D), the body coloured by von Mises stress and the points as spheres
  coloured by their force (or traction);
- view_footprint_indentation.png (with a footprint correction): the same, the points coloured
  by the local plastic indentation under their footprints;
- contact_views.pvsm: the same views in one layout; open it with
  `paraview --state OUTPUT_DIR/contact_views.pvsm`.
All at the frame of maximum force (from history.csv; the last frame without one), with the
case's units on the colour bars. Prints a line per image with its colour bars' titles.

Usage:  xvfb-run -a -s "-screen 0 1600x1200x24 -noreset" pvbatch scripts/render_views.py OUTPUT_DIR [CASE_NAME]
(a 24-bit screen: with xvfb-run's default screen the render window may fail to open; -noreset:
an X server that resets when its last client disconnects now and then refuses pvbatch)
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from contact_views import build  # noqa: E402
from paraview.simple import SaveScreenshot, SaveState  # noqa: E402

if len(sys.argv) < 2:
    sys.exit(__doc__)
out = os.path.abspath(sys.argv[1])
time, views, bars = build(out, sys.argv[2] if len(sys.argv) > 2 else None)
print("rendering at pseudo-time", time)
for name, view in views.items():
    target = os.path.join(out, "view_" + name + ".png")
    SaveScreenshot(target, view, ImageResolution=list(view.ViewSize))
    print("wrote", target, "(colour bars: " + "; ".join(bars[name]) + ")")
state = os.path.join(out, "contact_views.pvsm")
SaveState(state)
print("wrote", state, "(open it with: paraview --state " + state + ")")
