"""The standard ParaView views of a Stiction run, built once for both the PNG renderer
(`render_views.py`, pvbatch) and the saved state it writes (`contact_views.pvsm`, opened with
`paraview --state`), at the frame of maximum force (from history.csv: the largest compressive
force, or the most tensile where the interface is only pulled; the last frame without one):
- `von_mises` and `equivalent_plastic_strain` (if the material has it): the field on a section
  through the contact region (3D: the plane that holds the contact normal, through the region's
  middle or along a symmetry plane it touches; 2D and axisymmetric: the model's plane);
- `contact` (if the run has interface points): the contact region seen from the flat (3D) or
  from the side (2D), the body coloured by von Mises stress and the interface points as spheres
  coloured by their force, or their traction;
- `footprint_indentation` (with a footprint correction): the same, the points coloured by the
  local plastic indentation under their footprints.

Nothing here knows the shape: the contact region is where the interface points carry the load
at the frame shown (a force or traction of at least a tenth of the largest: a sphere's contact
disc, the process zone ahead of a crack; the whole body without points), its normal the axis
along which those points spread least, and every view is zoomed on it. Colour
bars carry the quantity and its unit from the `units` block of the run's summary.json.
"""
import csv
import glob
import json
import os

from paraview import servermanager
from paraview.simple import (AssignViewToLayout, Clip, ColorBy, CreateLayout, CreateView, GetAnimationScene,
                             GetColorTransferFunction, GetScalarBar, Glyph, PVDReader, Render, Show, Slice, Text)
from vtkmodules.util.numpy_support import vtk_to_numpy

VIEW_SIZE = [1000, 700]
WHITE = [1.0, 1.0, 1.0]
BLACK = [0.0, 0.0, 0.0]

# each output field: (what it is, which unit of the summary's `units` block it carries; None: none)
QUANTITIES = {
    "von_mises": ("von Mises stress", "stress"),
    "equivalent_plastic_strain": ("equivalent plastic strain", None),
    "force": ("force", "force"),
    "traction": ("normal traction", "stress"),
    "footprint_indentation": ("footprint indentation", "length"),
    "gap": ("gap", "length"),
    "damage": ("damage", None),
}


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
    """The output time closest to the largest compressive force in history.csv (the most
    tensile one when the interface is only pulled; the first interface's force column when there
    are several; the last frame without one)."""
    history = os.path.join(out, "history.csv")
    if not os.path.exists(history):
        return times[-1]
    with open(history) as f:
        rows = list(csv.DictReader(f))
    columns = [c for c in (rows[0].keys() if rows else []) if c == "force" or c.endswith(".force")]
    if not columns:
        return times[-1]
    forces = [(float(r[columns[0]]), float(r["time"])) for r in rows]
    if max(forces)[0] > 0.0:
        t_max = max(forces)[1]  # the largest compressive force
    elif min(forces)[0] < 0.0:
        t_max = min(forces)[1]  # a pulled interface: the most tensile force
    else:
        return times[-1]
    return min(times, key=lambda t: abs(t - t_max))


def units_of(out):
    """The `units` block of the run's summary.json (empty strings: the case declared none)."""
    try:
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f).get("units", {})
    except (OSError, ValueError):
        return {}


def title(field, units):
    """A colour bar's title: the quantity and its unit, e.g. 'von Mises stress (GPa)'."""
    what, unit = QUANTITIES.get(field, (field.replace("_", " "), None))
    if unit is None:
        return what + " (-)"
    return "%s (%s)" % (what, units.get(unit) or "case units")


def _fetch(source, time):
    source.UpdatePipeline(time)
    return servermanager.Fetch(source)


def _array(data, name):
    values = data.GetPointData().GetArray(name)
    return None if values is None else vtk_to_numpy(values)


def contact_region(point_readers, time, body_bounds):
    """(lower corner, upper corner, number of points) of the interface points that carry the load
    at `time`: a force (or traction) of at least a tenth of the largest in magnitude (the contact
    disc of a sphere, the process zone ahead of a crack); without those arrays, the points in
    contact or bonded; all points when none is; the body's bounds without points."""
    import numpy as np
    chosen = []
    for reader in point_readers:
        data = _fetch(reader, time)
        if data is None or data.GetNumberOfPoints() == 0:
            continue
        xyz = vtk_to_numpy(data.GetPoints().GetData())
        active = np.zeros(len(xyz), dtype=bool)
        load = _array(data, "force")
        if load is None:
            load = _array(data, "traction")
        if load is not None and np.abs(load).max() > 0.0:
            active = np.abs(load) >= LOADED_SHARE * np.abs(load).max()
        else:
            for flag in ("in_contact", "bonded"):
                values = _array(data, flag)
                if values is not None:
                    active |= values > 0.5
        chosen.append(xyz[active] if active.any() else xyz)
    if not chosen:
        b = body_bounds
        return [b[0], b[2], b[4]], [b[1], b[3], b[5]], 0
    xyz = np.concatenate(chosen)
    return list(xyz.min(axis=0)), list(xyz.max(axis=0)), len(xyz)


# a point carries the load where its force is at least this share of the largest
LOADED_SHARE = 0.1


class Frame:
    """Where to look: the contact normal (axis and the sign pointing into the body), the lateral
    axes, the section plane and the zoom, from the body's bounds and the contact region."""

    def __init__(self, body_bounds, low, high, n_points):
        lo = [body_bounds[0], body_bounds[2], body_bounds[4]]
        hi = [body_bounds[1], body_bounds[3], body_bounds[5]]
        size = [hi[k] - lo[k] for k in range(3)]
        largest = max(size)
        self.planar = size[2] <= 1e-9 * largest
        axes = [0, 1] if self.planar else [0, 1, 2]
        extent = [high[k] - low[k] for k in range(3)]
        # the contact normal: the axis along which the region spreads least (relative to the body)
        self.normal = min(axes, key=lambda k: (extent[k] / max(size[k], 1e-300), -k))
        self.center = [0.5 * (low[k] + high[k]) for k in range(3)]
        self.low, self.high = list(low), list(high)
        body_middle = 0.5 * (lo[self.normal] + hi[self.normal])
        self.into_body = 1.0 if body_middle >= self.center[self.normal] else -1.0
        lateral = [k for k in axes if k != self.normal]
        if self.planar:
            self.section_normal = 2
            self.across = lateral[0]
        else:
            # the section plane holds the normal and the lateral axis the body is longer along
            self.section_normal = min(lateral, key=lambda k: (size[k], k != 1))
            self.across = [k for k in lateral if k != self.section_normal][0]
            s = self.section_normal
            # a region that reaches a face of the body along the section's normal touches a
            # symmetry plane: cut there (just inside), else through the region's middle
            touches = 0.01 * size[s]
            if low[s] - lo[s] <= touches:
                self.center[s] = lo[s] + 1e-6 * size[s]
            elif hi[s] - high[s] <= touches:
                self.center[s] = hi[s] - 1e-6 * size[s]
        # how far the body reaches from the region into it (half of it is shown)
        self.depth = (hi[self.normal] - self.center[self.normal] if self.into_body > 0
                      else self.center[self.normal] - lo[self.normal])
        width = max(extent[k] for k in lateral)
        # a point contact still shows its neighbourhood: at least 5% of the body
        self.width = min(max(width, 0.05 * largest), largest)
        self.n_points = max(n_points, 1)
        self.glyph_size = self._glyph_size(extent, lateral)

    def _glyph_size(self, extent, lateral):
        spread = [max(extent[k], 1e-12 * self.width) for k in lateral]
        if len(spread) == 1:
            spacing = spread[0] / self.n_points
        else:
            spacing = (spread[0] * spread[1] / self.n_points) ** 0.5
        return min(0.8 * spacing, 0.05 * self.width)

    def unit(self, axis, sign=1.0):
        v = [0.0, 0.0, 0.0]
        v[axis] = sign
        return v

    def flat_side(self):
        """A point just on the flat's side of every loaded point."""
        p = list(self.center)
        edge = self.low if self.into_body > 0 else self.high
        p[self.normal] = edge[self.normal] - self.into_body * 1e-3 * self.width
        return p

    def side_camera(self, view):
        """Looking along the section's normal at the region and the body behind it, the body up
        and the lateral axis to the right."""
        scale = 0.9 * self.width
        focal = list(self.center)
        focal[self.normal] += self.into_body * min(0.5 * self.width, 0.5 * self.depth)
        # room on the right for the colour bars
        focal[self.across] += _BAR_ROOM * scale * view.ViewSize[0] / view.ViewSize[1]
        up = self.unit(self.normal, self.into_body)
        # the direction of view d with d x up = the lateral axis (so it points right)
        d = _cross(up, self.unit(self.across))
        position = [focal[k] - 10.0 * self.width * d[k] for k in range(3)]
        _camera(view, position, focal, up, scale)

    def flat_camera(self, view):
        """Looking from the flat at the contact region (3D), the lateral axis to the right."""
        scale = 0.75 * self.width
        d = self.unit(self.normal, self.into_body)
        up = self.unit(self.section_normal)
        if _cross(d, up)[self.across] < 0.0:
            up = self.unit(self.section_normal, -1.0)
        focal = list(self.center)
        focal[self.across] += _BAR_ROOM * scale * view.ViewSize[0] / view.ViewSize[1]
        position = [focal[k] - 10.0 * self.width * d[k] for k in range(3)]
        _camera(view, position, focal, up, scale)


# the share of a view's half-width kept free on its right for the colour bars
_BAR_ROOM = 0.25


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _field_range(source, field):
    for data in (source.PointData, source.CellData):
        if field in data.keys():
            low, high = data[field].GetRange()
            if high <= low:
                high = low + max(abs(low), 1.0) * 1e-6
            return low, high
    raise SystemExit("the run's output has no field '%s'" % field)


def _color(display, view, source, field, preset, units):
    association = "POINTS" if field in source.PointData.keys() else "CELLS"
    ColorBy(display, (association, field))
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset(preset, True)
    lut.RescaleTransferFunction(*_field_range(source, field))
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = title(field, units)
    bar.ComponentTitle = ""
    bar.TitleColor = BLACK
    bar.LabelColor = BLACK
    bar.RangeLabelFormat = "%-#.3g"
    return bar.Title


def _camera(view, position, focal, up, scale):
    Render(view)  # the first render resets the camera: set it afterwards
    view.CameraPosition = position
    view.CameraFocalPoint = focal
    view.CameraViewUp = up
    view.CameraParallelProjection = 1
    view.CameraParallelScale = scale
    Render(view)


def _new_view(time, size, heading):
    view = CreateView("RenderView")
    view.ViewSize = size
    view.ViewTime = time
    view.OrientationAxesVisibility = 1
    view.Background = WHITE
    view.UseColorPaletteForBackground = 0
    text = Text(Text=heading)
    shown = Show(text, view)
    shown.Color = BLACK
    shown.WindowLocation = "Upper Center"
    shown.FontSize = 20
    return view


def _section_view(body, time, frame, field, units, heading):
    view = _new_view(time, VIEW_SIZE, heading)
    source = body
    if not frame.planar:
        source = Slice(Input=body)
        source.SliceType = "Plane"
        source.SliceType.Origin = frame.center
        source.SliceType.Normal = frame.unit(frame.section_normal)
    source.UpdatePipeline(time)
    display = Show(source, view)
    bar = _color(display, view, source, field, "Jet", units)
    frame.side_camera(view)
    return view, [bar]


def _contact_view(body, point_readers, time, frame, units, heading, glyph_field=None):
    """The contact region: the body by von Mises, the points as glyphs coloured by `glyph_field`
    (default: their force, or traction)."""
    view = _new_view(time, [900, 800], heading)
    shown = body
    if not frame.planar:
        # what lies between the flat and the points goes (the other body of an interface inside
        # the model, e.g. blocks joined by cohesive elements)
        shown = Clip(Input=body)
        shown.ClipType = "Plane"
        shown.ClipType.Origin = frame.flat_side()
        shown.ClipType.Normal = frame.unit(frame.normal, frame.into_body)
        shown.Invert = 0
    shown.UpdatePipeline(time)
    surface = Show(shown, view)
    bars = [_color(surface, view, shown, "von_mises", "Jet", units)]
    for reader in point_readers:
        reader.UpdatePipeline(time)
        names = reader.PointData.keys()
        field = glyph_field or ("force" if "force" in names else "traction")
        if field not in names:
            continue
        glyphs = Glyph(Input=reader, GlyphType="Sphere")
        glyphs.ScaleArray = ["POINTS", "No scale array"]
        glyphs.ScaleFactor = frame.glyph_size
        glyphs.GlyphMode = "All Points"
        glyphs.UpdatePipeline(time)
        display = Show(glyphs, view)
        bars.append(_color(display, view, glyphs, field, "Cool to Warm", units))
    if frame.planar:
        frame.side_camera(view)
    else:
        frame.flat_camera(view)
    return view, bars


def build(out, name=None):
    """Builds the views of the run in `out` (case `name` if the folder holds several) in one
    layout; returns (time shown, {view name: view}, {view name: colour bar titles})."""
    body_file, point_files = run_files(out, name)
    case = os.path.basename(body_file)[:-4]
    units = units_of(out)
    body = PVDReader(FileName=body_file)
    times = list(body.TimestepValues) if body.TimestepValues else [0.0]
    time = frame_of_max_force(out, times)
    # the scene's time is what a saved state restores into every view
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = time
    body.UpdatePipeline(time)
    bounds = body.GetDataInformation().GetBounds()
    readers = [PVDReader(FileName=p) for p in point_files]
    low, high, n = contact_region(readers, time, bounds)
    frame = Frame(bounds, low, high, n)
    heading = "%s at t = %.4g" % (case, time)
    views, bars = {}, {}
    views["von_mises"], bars["von_mises"] = _section_view(body, time, frame, "von_mises", units, heading)
    if "equivalent_plastic_strain" in body.PointData.keys():
        views["equivalent_plastic_strain"], bars["equivalent_plastic_strain"] = _section_view(
            body, time, frame, "equivalent_plastic_strain", units, heading)
    if readers:
        views["contact"], bars["contact"] = _contact_view(body, readers, time, frame, units, heading)
        if "footprint_indentation" in readers[0].PointData.keys():
            views["footprint_indentation"], bars["footprint_indentation"] = _contact_view(
                body, readers, time, frame, units, heading, "footprint_indentation")
    layout = CreateLayout("Stiction " + case)
    for view in views.values():
        AssignViewToLayout(view=view, layout=layout)
    return time, views, bars
