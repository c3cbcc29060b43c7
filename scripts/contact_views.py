"""The standard ParaView views of a Stiction run, built once for both the PNG renderer
(`render_views.py`, pvbatch) and the saved state it writes (`contact_views.pvsm`, opened with
`paraview --state`): at the frame of maximum force (from history.csv; the last frame when the run
has no flat),
- `von_mises` and `equivalent_plastic_strain`: the field on the axial section of the body (the
  plane y = 0 in 3D, the r-z plane of an axisymmetric model), zoomed on the 250 nm around the
  pole;
- `contact`: the contact region seen from the flat, the body's surface coloured by von Mises
  stress and the interface points (asperities) as spheres coloured by their force.
Units are the case's; the Ru cases use nm, so the zoom is in nm.
"""
import csv
import glob
import os

from paraview.simple import (AssignViewToLayout, Clip, ColorBy, CreateLayout, CreateView, GetAnimationScene,
                             GetColorTransferFunction, Glyph, PVDReader, Render, Show, Slice)

# the contact zone around the pole (pole at the origin, body on +z, flat below)
ZOOM = 250.0
VIEW_SIZE = [1000, 700]


def run_files(out, name=None):
    """The body's .pvd and the interface points' .pvd files of the run in `out`."""
    pvds = sorted(glob.glob(os.path.join(out, "*.pvd")))
    if name is not None:
        pvds = [p for p in pvds if os.path.basename(p).startswith(name)]
    if not pvds:
        raise SystemExit("no .pvd in " + out + (" for case " + name if name else ""))
    # the body is <case>.pvd, each interface's points <case>_<interface>.pvd
    body = min(pvds, key=len)
    points = [p for p in pvds if p.startswith(body[:-4] + "_")]
    return body, points


def frame_of_max_force(out, times):
    """The output time closest to the maximum force in history.csv (the last frame without one)."""
    history = os.path.join(out, "history.csv")
    if not os.path.exists(history):
        return times[-1]
    with open(history) as f:
        rows = list(csv.DictReader(f))
    if not rows or "force" not in rows[0]:
        return times[-1]
    t_max = float(max(rows, key=lambda r: float(r["force"]))["time"])
    return min(times, key=lambda t: abs(t - t_max))


def _color(display, view, source, field, preset):
    ColorBy(display, ("POINTS", field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset(preset, True)
    lut.RescaleTransferFunction(*source.PointData[field].GetRange())
    display.SetScalarBarVisibility(view, True)


def _camera(view, position, focal, up, scale):
    Render(view)  # the first render resets the camera: set it afterwards
    view.CameraPosition = position
    view.CameraFocalPoint = focal
    view.CameraViewUp = up
    view.CameraParallelProjection = 1
    view.CameraParallelScale = scale
    Render(view)


def _section_view(body, time, is_3d, field):
    view = CreateView("RenderView")
    view.ViewSize = VIEW_SIZE
    view.ViewTime = time
    view.OrientationAxesVisibility = 0
    source = body
    if is_3d:
        near = Clip(Input=body)
        near.ClipType = "Sphere"
        near.ClipType.Center = [0.0, 0.0, 0.0]
        near.ClipType.Radius = 2.0 * ZOOM
        near.Invert = 1
        source = Slice(Input=near)
        source.SliceType = "Plane"
        source.SliceType.Origin = [0.0, 0.0, 0.0]
        source.SliceType.Normal = [0.0, 1.0, 0.0]
    source.UpdatePipeline(time)
    display = Show(source, view)
    _color(display, view, source, field, "Jet")
    if is_3d:
        _camera(view, [0.0, -4 * ZOOM, 0.45 * ZOOM], [0.0, 0.0, 0.45 * ZOOM], [0.0, 0.0, 1.0], 0.65 * ZOOM)
    else:
        _camera(view, [0.45 * ZOOM, 0.45 * ZOOM, 4 * ZOOM], [0.45 * ZOOM, 0.45 * ZOOM, 0.0], [0.0, 1.0, 0.0],
                0.65 * ZOOM)
    return view


def _contact_view(body, points, time, is_3d, glyph_field=None):
    """The contact region from the flat: the body's surface by von Mises, points as glyphs
    coloured by `glyph_field` (default: their force, or traction)."""
    view = CreateView("RenderView")
    view.ViewSize = [900, 800]
    view.ViewTime = time
    if is_3d:
        near = Clip(Input=body)
        near.ClipType = "Sphere"
        near.ClipType.Center = [0.0, 0.0, 0.0]
        near.ClipType.Radius = ZOOM
        near.Invert = 1
        near.UpdatePipeline(time)
        surface = Show(near, view)
        _color(surface, view, near, "von_mises", "Jet")
    for p in points:
        reader = PVDReader(FileName=p)
        reader.UpdatePipeline(time)
        names = [reader.PointData.GetArray(i).Name for i in range(len(reader.PointData))]
        field = glyph_field or ("force" if "force" in names else "traction")
        glyphs = Glyph(Input=reader, GlyphType="Sphere")
        glyphs.ScaleArray = ["POINTS", "No scale array"]
        glyphs.ScaleFactor = 0.025 * ZOOM
        glyphs.GlyphMode = "All Points"
        glyphs.UpdatePipeline(time)
        display = Show(glyphs, view)
        _color(display, view, glyphs, field, "Cool to Warm")
    if is_3d:
        _camera(view, [0.0, 0.0, -10 * ZOOM], [0.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0.56 * ZOOM)
    else:
        _camera(view, [0.5 * ZOOM, 0.0, 4 * ZOOM], [0.5 * ZOOM, 0.0, 0.0], [0.0, 1.0, 0.0], 0.56 * ZOOM)
    return view


def build(out, name=None):
    """Builds the views of the run in `out` (case `name` if the folder holds several) in one
    layout; returns (time shown, {view name: view})."""
    body_file, point_files = run_files(out, name)
    body = PVDReader(FileName=body_file)
    times = list(body.TimestepValues) if body.TimestepValues else [0.0]
    time = frame_of_max_force(out, times)
    # the scene's time is what a saved state restores into every view
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = time
    body.UpdatePipeline(time)
    arrays = [body.PointData.GetArray(i).Name for i in range(len(body.PointData))]
    is_3d = "stress_rr_zz_tt_rz" not in arrays
    views = {"von_mises": _section_view(body, time, is_3d, "von_mises")}
    if "equivalent_plastic_strain" in arrays:
        views["equivalent_plastic_strain"] = _section_view(body, time, is_3d, "equivalent_plastic_strain")
    if point_files:
        views["contact"] = _contact_view(body, point_files, time, is_3d)
        first = PVDReader(FileName=point_files[0])
        first.UpdatePipeline(time)
        if "footprint_indentation" in [first.PointData.GetArray(i).Name for i in range(len(first.PointData))]:
            # the local plastic indentation under each footprint (a footprint correction)
            views["footprint_indentation"] = _contact_view(body, point_files, time, is_3d, "footprint_indentation")
    layout = CreateLayout("Stiction " + os.path.basename(body_file)[:-4])
    for view in views.values():
        AssignViewToLayout(view=view, layout=layout)
    return time, views
