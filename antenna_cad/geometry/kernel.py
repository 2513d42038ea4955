"""The CAD kernel: OpenCASCADE through OCP, function-style, on plain ``TopoDS_Shape`` values.

The one module (with :mod:`antenna_cad.export.step`) that builds OCCT shapes: edges, wires and faces
from points, prisms and solids of revolution, primitives, booleans, placement and the read-backs
(volume, area, bounding box, validity). Only the OCP modules used here are imported: build123d's
import alone took ~165 MB more and ~2 s. Booleans run in parallel and are cleaned
(faces of one surface unified) as build123d did, so the solids and their STEP stay the same.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Builder, BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve, BRepAdaptor_Surface
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepBuilderAPI import (BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon,
                                BRepBuilderAPI_MakeWire)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepGProp import BRepGProp
from OCP.BRepOffset import BRepOffset_MakeOffset, BRepOffset_Skin
from OCP.BRepPrimAPI import (BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakePrism,
                             BRepPrimAPI_MakeRevol, BRepPrimAPI_MakeSphere)
from OCP.collections import Array1_gp_Vec, Array2_gp_Pnt, HArray1_bool, HArray1_gp_Pnt, List_TopoDS_Shape
from OCP.GC import GC_MakeArcOfCircle, GC_MakeCircle
from OCP.Geom import Geom_Hyperbola, Geom_TrimmedCurve
from OCP.GeomAbs import GeomAbs_Intersection, GeomAbs_Plane
from OCP.GeomAPI import GeomAPI_Interpolate, GeomAPI_PointsToBSplineSurface
from OCP.gp import gp_Ax1, gp_Ax2, gp_Ax3, gp_Dir, gp_Hypr, gp_Pnt, gp_Trsf, gp_Vec
from OCP.GeomConvert import GeomConvert
from OCP.GProp import GProp_GProps
from OCP.Precision import Precision
from OCP.ShapeFix import ShapeFix_Face, ShapeFix_Shape
from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TopAbs import TopAbs_COMPOUND, TopAbs_FACE, TopAbs_SOLID, TopAbs_VERTEX
from OCP.TopExp import TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS, TopoDS_Compound, TopoDS_Edge, TopoDS_Face, TopoDS_Iterator, TopoDS_Shape, TopoDS_Wire

Shape = TopoDS_Shape
XYZ = Sequence[float]


def _pnt(p: XYZ) -> gp_Pnt:
    return gp_Pnt(float(p[0]), float(p[1]), float(p[2]))


def _dir(v: XYZ) -> gp_Dir:
    return gp_Dir(float(v[0]), float(v[1]), float(v[2]))


# --- edges, wires, faces -------------------------------------------------------------------------

def line(a: XYZ, b: XYZ) -> TopoDS_Edge:
    return BRepBuilderAPI_MakeEdge(_pnt(a), _pnt(b)).Edge()


def arc(a: XYZ, mid: XYZ, b: XYZ) -> TopoDS_Edge:
    """Circular arc from ``a`` through ``mid`` to ``b``."""
    return BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(_pnt(a), _pnt(mid), _pnt(b)).Value()).Edge()


def curve_edge(curve) -> TopoDS_Edge:
    """An edge on a whole ``Geom_Curve``."""
    return BRepBuilderAPI_MakeEdge(curve).Edge()


def hyperbola_arc(z_centre: float, a: float, b: float, u_from: float, u_to: float) -> TopoDS_Edge:
    """Arc of the hyperbola z = z_centre + a·cosh u, x = b·sinh u (y = 0) for u in [u_from, u_to],
    as its exact rational B-spline (the form every STEP reader takes; see geometry.profiles)."""
    conic = Geom_Hyperbola(gp_Hypr(gp_Ax2(gp_Pnt(0, 0, z_centre), gp_Dir(0, 1, 0), gp_Dir(0, 0, 1)), a, b))
    return curve_edge(GeomConvert.CurveToBSplineCurve_s(Geom_TrimmedCurve(conic, u_from, u_to)))


def spline(points: Sequence[XYZ], tangents: Sequence[XYZ]) -> TopoDS_Edge:
    """C¹ interpolating B-spline through ``points`` with a tangent at each (scaled to the chord
    parametrisation), to 1e-6 mm."""
    pnts = HArray1_gp_Pnt(1, len(points))
    for i, p in enumerate(points, 1):
        pnts.SetValue(i, _pnt(p))
    builder = GeomAPI_Interpolate(pnts, False, 1e-6)
    vecs, enabled = Array1_gp_Vec(1, len(tangents)), HArray1_bool(1, len(tangents))
    for i, t in enumerate(tangents, 1):
        vecs.SetValue(i, gp_Vec(float(t[0]), float(t[1]), float(t[2])))
        enabled.SetValue(i, True)
    builder.Load(vecs, enabled, True)
    builder.Perform()
    if not builder.IsDone():
        raise ValueError("B-spline interpolation failed")
    return BRepBuilderAPI_MakeEdge(builder.Curve()).Edge()


def wire(edges: Iterable[TopoDS_Edge]) -> TopoDS_Wire:
    """One wire through connected edges (in any order and orientation)."""
    items = List_TopoDS_Shape()
    for e in edges:
        items.Append(e)
    builder = BRepBuilderAPI_MakeWire()
    builder.Add(items)
    builder.Build()
    if not builder.IsDone():
        raise ValueError(f"edges do not make one wire (BRepBuilderAPI_MakeWire error {builder.Error()})")
    return builder.Wire()


def polygon(points: Iterable[XYZ]) -> TopoDS_Wire:
    """Closed polygon wire through ``points`` (the last joined back to the first)."""
    builder = BRepBuilderAPI_MakePolygon()
    for p in points:
        builder.Add(_pnt(p))
    builder.Close()
    return builder.Wire()


def face(outer: TopoDS_Wire, holes: Iterable[TopoDS_Wire] = ()) -> TopoDS_Face:
    """Planar face bounded by ``outer`` with ``holes`` as inner wires (wire orientations fixed)."""
    builder = BRepBuilderAPI_MakeFace(_fixed_wire(outer), True)
    for h in holes:
        builder.Add(_fixed_wire(h))
    builder.Build()
    if not builder.IsDone():
        raise ValueError(f"cannot build a planar face (BRepBuilderAPI_MakeFace error {builder.Error()})")
    fix = ShapeFix_Face(builder.Face())
    fix.FixOrientation()
    fix.Perform()
    return TopoDS.Face(fix.Result())


def _fixed_wire(w: TopoDS_Wire) -> TopoDS_Wire:
    fix = ShapeFix_Shape(w)
    fix.Perform()
    return TopoDS.Wire(fix.Shape())


def disc(x: float, y: float, r: float) -> TopoDS_Face:
    """Disc of radius ``r`` centred on (x, y) in the plane z = 0."""
    circle = GC_MakeCircle(gp_Ax2(gp_Pnt(x, y, 0.0), gp_Dir(0, 0, 1)), r).Value()
    return face(wire([curve_edge(circle)]))


def rectangle(x: float, y: float, width: float, height: float) -> TopoDS_Face:
    """Rectangle ``width`` × ``height`` centred on (x, y) in the plane z = 0."""
    w, h = width / 2, height / 2
    return face(polygon([(x - w, y - h, 0), (x + w, y - h, 0), (x + w, y + h, 0), (x - w, y + h, 0)]))


def surface(grid: Sequence[Sequence[XYZ]], tolerance_mm: float) -> TopoDS_Face:
    """B-spline surface (degree 1–3) approximating a grid of points to ``tolerance_mm``."""
    pts = Array2_gp_Pnt(1, len(grid), 1, len(grid[0]))
    for i, row in enumerate(grid, 1):
        for j, p in enumerate(row, 1):
            pts.SetValue(i, j, _pnt(p))
    builder = GeomAPI_PointsToBSplineSurface(pts, DegMin=1, DegMax=3, Tol3D=tolerance_mm)
    if not builder.IsDone():
        raise ValueError("B-spline surface approximation failed")
    return BRepBuilderAPI_MakeFace(builder.Surface(), Precision.Confusion_s()).Face()


# --- solids --------------------------------------------------------------------------------------

def extrude(shape: Shape, vector: XYZ) -> Shape:
    """Prism of a face (or faces) swept along ``vector``."""
    return clean(BRepPrimAPI_MakePrism(shape, gp_Vec(*map(float, vector))).Shape())


def plate(outer: TopoDS_Wire, holes: Iterable[TopoDS_Wire], vector: XYZ) -> Shape:
    """A planar face (counter-clockwise ``outer``, clockwise ``holes``, taken as they are: no wire
    fixing or cleaning, linear in thousands of holes) swept along ``vector``."""
    builder = BRepBuilderAPI_MakeFace(outer, True)
    for h in holes:
        builder.Add(h)
    return BRepPrimAPI_MakePrism(builder.Face(), gp_Vec(*map(float, vector))).Shape()


def revolve_z(profile: TopoDS_Face) -> Shape:
    """The face turned once (360°) about the Z axis."""
    axis = gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))
    return clean(BRepPrimAPI_MakeRevol(profile, axis, 2 * math.pi, True).Shape())


def box(corner: XYZ, size: XYZ) -> Shape:
    """Axis-aligned box from its minimum ``corner`` with edge lengths ``size``."""
    return BRepPrimAPI_MakeBox(_pnt(corner), *map(float, size)).Shape()


def cylinder(radius: float, height: float, base: XYZ = (0, 0, 0), axis: XYZ = (0, 0, 1)) -> Shape:
    """Cylinder from its ``base`` centre along ``axis``."""
    return BRepPrimAPI_MakeCylinder(gp_Ax2(_pnt(base), _dir(axis)), radius, height).Shape()


def sphere(radius: float) -> Shape:
    return BRepPrimAPI_MakeSphere(radius).Shape()


def thicken(sheet: TopoDS_Face, depth: float) -> Shape:
    """A solid from a (curved) face offset by ``depth`` along its normal."""
    builder = BRepOffset_MakeOffset()
    builder.Initialize(sheet, Offset=depth, Tol=1.0e-5, Mode=BRepOffset_Skin, Intersection=True,
                       SelfInter=False, Join=GeomAbs_Intersection, Thickening=True, RemoveIntEdges=True)
    builder.MakeOffsetShape()
    return TopoDS.Solid(builder.Shape())


def fuse(shapes: Sequence[Shape]) -> Shape:
    """Boolean union of ``shapes`` (one batched operation)."""
    return shapes[0] if len(shapes) == 1 else _boolean(BRepAlgoAPI_Fuse(), shapes[:1], shapes[1:])


def cut(shape: Shape, tools: Sequence[Shape]) -> Shape:
    """``shape`` less ``tools`` (one batched operation)."""
    return shape if not tools else _boolean(BRepAlgoAPI_Cut(), [shape], tools)


def _boolean(op, args: Sequence[Shape], tools: Sequence[Shape]) -> Shape:
    a, t = List_TopoDS_Shape(), List_TopoDS_Shape()
    for s in args:
        a.Append(s)
    for s in tools:
        t.Append(s)
    op.SetArguments(a)
    op.SetTools(t)
    op.SetRunParallel(True)
    op.Build()
    if not op.IsDone():
        raise RuntimeError("boolean operation failed")
    result = clean(op.Shape())
    if result.ShapeType() == TopAbs_COMPOUND:         # one shape in a compound: the shape itself
        inner = list(_children(result))
        if len(inner) == 1:
            return inner[0]
    return result


def clean(shape: Shape) -> Shape:
    """Faces and edges lying on one surface or curve merged (no internal edges), best effort."""
    upgrader = ShapeUpgrade_UnifySameDomain(shape, True, True, True)
    upgrader.AllowInternalEdges(False)
    try:
        upgrader.Build()
    except Exception:       # OCP raises OCCT failures as bare Exception; the shape stays usable as is
        return shape
    return upgrader.Shape()


def compound(shapes: Iterable[Shape]) -> TopoDS_Compound:
    """A plain compound of ``shapes`` (no copy)."""
    result, builder = TopoDS_Compound(), BRep_Builder()
    builder.MakeCompound(result)
    for s in shapes:
        builder.Add(result, s)
    return result


def _children(shape: Shape):
    it = TopoDS_Iterator(shape)
    while it.More():
        yield it.Value()
        it.Next()


# --- placement -----------------------------------------------------------------------------------

def _moved(shape: Shape, trsf: gp_Trsf) -> Shape:
    return shape.Moved(TopLoc_Location(trsf))


def translate(shape: Shape, offset: XYZ) -> Shape:
    trsf = gp_Trsf()
    trsf.SetTranslation(gp_Vec(*map(float, offset)))
    return _moved(shape, trsf)


def rotate(shape: Shape, axis: XYZ, degrees: float) -> Shape:
    """Turned by ``degrees`` about ``axis`` through the origin."""
    trsf = gp_Trsf()
    trsf.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), _dir(axis)), math.radians(degrees))
    return _moved(shape, trsf)


def place(shape: Shape, origin: XYZ, z_dir: XYZ, x_dir: XYZ) -> Shape:
    """The shape's local frame put at ``origin`` with its Z along ``z_dir`` and X along ``x_dir``."""
    trsf = gp_Trsf()
    trsf.SetTransformation(gp_Ax3(_pnt(origin), _dir(z_dir), _dir(x_dir)))
    trsf.Invert()
    return _moved(shape, trsf)


# --- read-backs ----------------------------------------------------------------------------------

def solids(shape: Shape) -> list[Shape]:
    return _explore(shape, TopAbs_SOLID)


def faces(shape: Shape) -> list[TopoDS_Face]:
    return [TopoDS.Face(f) for f in _explore(shape, TopAbs_FACE)]


def _explore(shape: Shape, kind) -> list[Shape]:
    out, explorer = [], TopExp_Explorer(shape, kind)
    while explorer.More():
        out.append(explorer.Current())
        explorer.Next()
    return out


def volume(shape: Shape) -> float:
    """Volume of a solid, or the sum over a compound's solids (each integrated on its own: GProp
    over a whole compound of thin sanding rings strayed by 1.5e-6 from the solids' sum)."""
    if shape.ShapeType() == TopAbs_COMPOUND:
        return sum(volume(s) for s in solids(shape))
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props)
    return props.Mass()


def area(shape: Shape) -> float:
    props = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, props)
    return props.Mass()


def is_valid(shape: Shape) -> bool:
    """BRepCheck of the shape's topology and geometry."""
    check = BRepCheck_Analyzer(shape)
    check.SetParallel(True)
    return bool(check.IsValid())


def bounding_box(shapes: Iterable[Shape]) -> tuple[np.ndarray, np.ndarray]:
    """(min, max) corners of the tight (optimal) bounding box of ``shapes`` together."""
    bnd = Bnd_Box()
    for s in shapes:
        BRepBndLib.AddOptimal_s(s, bnd, False, False)   # the exact geometry, not a mesh
    lo, hi = bnd.CornerMin(), bnd.CornerMax()
    return np.array([lo.X(), lo.Y(), lo.Z()]), np.array([hi.X(), hi.Y(), hi.Z()])


def vertices(shape: Shape) -> np.ndarray:
    """(n, 3) coordinates of the shape's vertices (each position once)."""
    pts = [BRep_Tool.Pnt_s(TopoDS.Vertex(v)) for v in _explore(shape, TopAbs_VERTEX)]
    return np.unique(np.array([(p.X(), p.Y(), p.Z()) for p in pts]).reshape(-1, 3), axis=0)


def plane_normal(f: TopoDS_Face) -> np.ndarray | None:
    """The unit normal of a planar face's plane (up to sign); None for a curved face."""
    adaptor = BRepAdaptor_Surface(f)
    if adaptor.GetType() != GeomAbs_Plane:
        return None
    d = adaptor.Plane().Axis().Direction()
    return np.array([d.X(), d.Y(), d.Z()])


def edge_points(edge: TopoDS_Edge, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3), first derivatives (n, 3)) at ``n`` equal steps of the edge's parameter."""
    adaptor = BRepAdaptor_Curve(edge)
    p, v = gp_Pnt(), gp_Vec()
    pts, ders = [], []
    for u in np.linspace(adaptor.FirstParameter(), adaptor.LastParameter(), n):
        adaptor.D1(float(u), p, v)
        pts.append((p.X(), p.Y(), p.Z()))
        ders.append((v.X(), v.Y(), v.Z()))
    return np.array(pts), np.array(ders)
