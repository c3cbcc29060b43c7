"""Renders a Stiction run's standard views to PNG with ParaView (pvbatch), like the reference
paper's Fig. 5, and saves them as a ParaView state to open and explore interactively (the views
are built by `contact_views.py`, beside this script):
- view_von_mises.png, view_equivalent_plastic_strain.png (if the material has it): the field on
  the axial section, zoomed on the contact zone (the 250 nm around the pole);
- view_contact.png (if the run has interface points): the contact region seen from the flat, the
  body coloured by von Mises stress, the asperities as spheres coloured by their force;
- view_footprint_indentation.png (with a footprint correction): the same, the asperities
  coloured by the local plastic indentation under their footprints (the continuum's flow below
  the mesh scale);
- contact_views.pvsm: the same views in one layout; open it with
  `paraview --state OUTPUT_DIR/contact_views.pvsm`.
All at the frame of maximum force (from history.csv; the last frame without one). Units as in
the case.

Usage:  xvfb-run -a -s "-screen 0 1600x1200x24" pvbatch scripts/render_views.py OUTPUT_DIR [CASE_NAME]
(a 24-bit screen: with xvfb-run's default screen the render window may fail to open)
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from contact_views import build  # noqa: E402
from paraview.simple import SaveScreenshot, SaveState  # noqa: E402

if len(sys.argv) < 2:
    sys.exit(__doc__)
out = os.path.abspath(sys.argv[1])
time, views = build(out, sys.argv[2] if len(sys.argv) > 2 else None)
print("rendering at pseudo-time", time)
for name, view in views.items():
    target = os.path.join(out, "view_" + name + ".png")
    SaveScreenshot(target, view, ImageResolution=list(view.ViewSize))
    print("wrote", target)
state = os.path.join(out, "contact_views.pvsm")
SaveState(state)
print("wrote", state, "(open it with: paraview --state " + state + ")")
