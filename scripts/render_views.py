"""Renders a Stiction run's standard views to PNG with ParaView (pvbatch), like the reference
paper's Fig. 5: von Mises stress and equivalent plastic strain on the axial section of the
sphere, and the asperity (or interface point) forces over the contact region, at the frame of
maximum force (from history.csv; the last frame if the run has no interface).

Usage:  xvfb-run -a pvbatch scripts/render_views.py OUTPUT_DIR [CASE_NAME]
Writes OUTPUT_DIR/view_von_mises.png, view_equivalent_plastic_strain.png (if the material has
it) and view_interface_forces.png (if the run has an interface with points). The section is the
plane through the axis (normal y, through the origin); the view is zoomed on the contact zone
(the 250 nm around the pole). Units as in the case.
"""
import glob
import os
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction,
                             PVDReader, Render, SaveScreenshot, Show, Slice)

out = sys.argv[1]
pvds = sorted(glob.glob(os.path.join(out, "*.pvd")))
name = sys.argv[2] if len(sys.argv) > 2 else None
solid = [p for p in pvds if name is None or os.path.basename(p) == name + ".pvd"]
solid = [p for p in solid if p.count("_") == 0 or not any(p.endswith("_" + s + ".pvd") for s in ("asperities", "flat"))]
if not solid:
    sys.exit("no solid .pvd in " + out)
body_file = min(solid, key=len)
body = PVDReader(FileName=body_file)
times = list(body.TimestepValues) if body.TimestepValues else [0.0]
last = times[-1]
history = os.path.join(out, "history.csv")
if os.path.exists(history):
    import csv
    rows = list(csv.DictReader(open(history)))
    if rows and "force" in rows[0]:
        t_max = float(max(rows, key=lambda r: float(r["force"]))["time"])
        last = min(times, key=lambda t: abs(t - t_max))
print("rendering at pseudo-time", last)
body.UpdatePipeline(last)
arrays = [body.PointData.GetArray(i).Name for i in range(len(body.PointData))]
is_3d = "stress_rr_zz_tt_rz" not in arrays


def section_view(field, title_png):
    view = CreateView("RenderView")
    view.ViewSize = [1000, 700]
    view.ViewTime = last
    view.OrientationAxesVisibility = 0
    source = body
    if is_3d:
        source = Slice(Input=body)
        source.SliceType = "Plane"
        source.SliceType.Origin = [0.0, 0.0, 0.0]
        source.SliceType.Normal = [0.0, 1.0, 0.0]
    display = Show(source, view)
    ColorBy(display, ("POINTS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Jet", True)
    display.SetScalarBarVisibility(view, True)
    lut.RescaleTransferFunction(*source.PointData[field].GetRange())
    Render(view)  # the first render resets the camera: set it afterwards
    # zoom on the contact zone: the 250 nm around the pole (in the x-z plane for 3D, x-y axisym)
    if is_3d:
        view.CameraPosition = [0.0, -2000.0, 120.0]
        view.CameraFocalPoint = [0.0, 0.0, 120.0]
        view.CameraViewUp = [0.0, 0.0, 1.0]
    else:
        view.CameraPosition = [120.0, 120.0, 2000.0]
        view.CameraFocalPoint = [120.0, 120.0, 0.0]
        view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 160.0
    Render(view)
    SaveScreenshot(os.path.join(out, title_png), view, ImageResolution=[1000, 700])
    print("wrote", os.path.join(out, title_png))


section_view("von_mises", "view_von_mises.png")
if "equivalent_plastic_strain" in arrays:
    section_view("equivalent_plastic_strain", "view_equivalent_plastic_strain.png")

points = [p for p in pvds if p != body_file]
for p in points:
    reader = PVDReader(FileName=p)
    reader.UpdatePipeline(last)
    names = [reader.PointData.GetArray(i).Name for i in range(len(reader.PointData))]
    field = "force" if "force" in names else "traction"
    view = CreateView("RenderView")
    view.ViewSize = [900, 800]
    view.ViewTime = last
    display = Show(reader, view)
    display.SetRepresentationType("Points")
    display.PointSize = 8
    display.RenderPointsAsSpheres = 1
    ColorBy(display, ("POINTS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(*reader.PointData[field].GetRange())
    display.SetScalarBarVisibility(view, True)
    Render(view)  # the first render resets the camera: set it afterwards
    # look at the contact region from the flat (below, along +z)
    view.CameraPosition = [0.0, 0.0, -3000.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 140.0
    Render(view)
    target = os.path.join(out, "view_interface_forces.png" if len(points) == 1 else
                          "view_" + os.path.basename(p)[:-4] + ".png")
    SaveScreenshot(target, view, ImageResolution=[900, 800])
    print("wrote", target)
