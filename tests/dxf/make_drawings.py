#!/usr/bin/python3
"""Writes the test drawings of camgen's DXF reader with ezdxf (an independent writer), and for
each NAME.dxf a NAME.expected.json with the geometry ezdxf was given, in world coordinates:

  {"units": insunits,
   "points": [[x, y], ...], "circles": [[cx, cy, r], ...],
   "paths": [{"start": [x, y], "closed": bool,
              "segments": [[x, y] | [x, y, cx, cy, "cw"|"ccw"], ...]}, ...]}

in the order of the model space (inserts expanded in place, after the plain entities: camgen
lists a drawing's own entities first, then those of its inserts). Curves that camgen fits by
lines (ELLIPSE, SPLINE) are given as {"curve": [[x, y], ...]} of points on the curve instead.
Run it from anywhere: `/usr/bin/python3 tests/dxf/make_drawings.py` (the drawings are
committed; run it again only to change them, and read the diff).
"""
import json
import math
import pathlib

import ezdxf
from ezdxf.math import Vec3

HERE = pathlib.Path(__file__).resolve().parent


def arc_points(cx, cy, r, a0, a1):
    """Start and end of a CCW arc from a0 to a1 degrees."""
    return ((cx + r * math.cos(math.radians(a0)), cy + r * math.sin(math.radians(a0))),
            (cx + r * math.cos(math.radians(a1)), cy + r * math.sin(math.radians(a1))))


def bulge_centre(p, q, b):
    cx, cy = (p[0] + q[0]) / 2, (p[1] + q[1]) / 2
    dx, dy = q[0] - p[0], q[1] - p[1]
    c = math.hypot(dx, dy)
    off = c * (1 - b * b) / (4 * b)
    return cx - dy / c * off, cy + dx / c * off


def poly_path(vertices, closed, mirror=False):
    """vertices: (x, y, bulge) in OCS; mirror: OCS of extrusion -Z (x -> -x, arcs turn cw)."""
    m = (lambda p: (-p[0], p[1])) if mirror else (lambda p: p)
    segs = []
    pts = list(vertices) + ([vertices[0]] if closed else [])
    for (x0, y0, b), (x1, y1, _) in zip(pts, pts[1:]):
        if b == 0:
            segs.append(list(m((x1, y1))))
        else:
            c = bulge_centre((x0, y0), (x1, y1), b)
            d = "ccw" if b > 0 else "cw"
            if mirror:
                d = "cw" if d == "ccw" else "ccw"
            segs.append(list(m((x1, y1))) + list(m(c)) + [d])
    return {"start": list(m(vertices[0][:2])), "closed": closed, "segments": segs}


def new(units):
    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = units
    return doc


def save(doc, name, expected):
    doc.saveas(HERE / f"{name}.dxf")
    (HERE / f"{name}.expected.json").write_text(json.dumps(expected, indent=1) + "\n")


def entities():
    """Every entity type once, on layers, in millimetres."""
    doc = new(4)
    for name, colour in (("OUTLINE", 1), ("HOLES", 3), ("CURVES", 5)):
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    exp = {"units": 4, "points": [], "circles": [], "paths": []}
    msp.add_line((0, 0), (40.5, 0), dxfattribs={"layer": "OUTLINE"})
    exp["paths"].append({"start": [0, 0], "closed": False, "segments": [[40.5, 0]]})
    msp.add_arc((40.5, 10), 10, -90, 90, dxfattribs={"layer": "OUTLINE"})
    s, e = arc_points(40.5, 10, 10, -90, 90)
    exp["paths"].append({"start": list(s), "closed": False, "segments": [list(e) + [40.5, 10, "ccw"]]})
    msp.add_circle((12.25, 7.75), 3.3, dxfattribs={"layer": "HOLES"})
    exp["circles"].append([12.25, 7.75, 3.3])
    msp.add_point((5.125, 6.5), dxfattribs={"layer": "HOLES"})
    exp["points"].append([5.125, 6.5])
    v = [(60, 0, 0), (80, 0, 0.41421356237309503), (90, 10, 0), (90, 20, -0.5), (60, 20, 0)]
    msp.add_lwpolyline(v, format="xyb", close=True, dxfattribs={"layer": "OUTLINE"})
    exp["paths"].append(poly_path(v, True))
    v2 = [(0, 30, 0), (10, 30, 1.0), (20, 30, 0), (30, 35, 0)]
    pl = msp.add_polyline2d([(x, y) for x, y, _ in v2], dxfattribs={"layer": "OUTLINE"})
    for vertex, (_, _, b) in zip(pl.vertices, v2):
        vertex.dxf.bulge = b
    exp["paths"].append(poly_path(v2, False))
    # An ellipse that is a circle (arcs), a real one and a spline (points on the curve).
    msp.add_ellipse((100, 50), major_axis=(5, 0), ratio=1.0, start_param=0, end_param=math.pi, dxfattribs={"layer": "CURVES"})
    exp["paths"].append({"start": [105, 50], "closed": False, "segments": [[95, 50, 100, 50, "ccw"]]})
    el = msp.add_ellipse((100, 80), major_axis=(0, 12), ratio=0.5, dxfattribs={"layer": "CURVES"})
    params = [i * 2 * math.pi / 16 for i in range(17)]
    exp["paths"].append({"closed": True, "curve": [[p.x, p.y] for p in el.construction_tool().vertices(params)]})
    ctrl = [(120, 0), (130, 10), (140, -5), (150, 10), (160, 0)]
    sp = msp.add_open_spline(ctrl, degree=3, dxfattribs={"layer": "CURVES"})
    tool = sp.construction_tool()
    exp["paths"].append({"closed": False, "curve": [[p.x, p.y] for p in tool.points([tool.max_t * i / 20 for i in range(21)])]})
    save(doc, "entities", exp)


def ocs():
    """Arcs, circles and a polyline of extrusion (0, 0, -1): mirrored in X."""
    doc = new(4)
    msp = doc.modelspace()
    exp = {"units": 4, "points": [], "circles": [], "paths": []}
    msp.add_arc((10, 5), 4, 0, 90, dxfattribs={"extrusion": (0, 0, -1)})
    s, e = arc_points(10, 5, 4, 0, 90)
    exp["paths"].append({"start": [-s[0], s[1]], "closed": False, "segments": [[-e[0], e[1], -10, 5, "cw"]]})
    msp.add_circle((20, 7), 2.5, dxfattribs={"extrusion": (0, 0, -1)})
    exp["circles"].append([-20, 7, 2.5])
    v = [(30, 0, 0), (40, 0, 0.5), (40, 10, 0)]
    msp.add_lwpolyline(v, format="xyb", dxfattribs={"extrusion": (0, 0, -1)})
    exp["paths"].append(poly_path(v, False, mirror=True))
    save(doc, "ocs", exp)


def blocks():
    """A block of a hole and a slot arc, inserted through another block (nested), rotated,
    scaled, mirrored, and as an array."""
    doc = new(4)
    hole = doc.blocks.new("HOLE", base_point=(1, 1))
    hole.add_circle((1, 1), 2.0, dxfattribs={"layer": "0"})
    hole.add_arc((6, 1), 1.0, 0, 180, dxfattribs={"layer": "0"})
    pair = doc.blocks.new("PAIR", base_point=(0, 0))
    pair.add_blockref("HOLE", (10, 0), dxfattribs={"rotation": 90})
    pair.add_blockref("HOLE", (-10, 0), dxfattribs={"xscale": -1, "yscale": 1})
    msp = doc.modelspace()
    doc.layers.add("HOLES")
    exp = {"units": 4, "points": [], "circles": [], "paths": []}

    def place(x, y, ins, rot, sx, sy, base=(0, 0)):
        x, y = (x - base[0]) * sx, (y - base[1]) * sy
        c, s = math.cos(math.radians(rot)), math.sin(math.radians(rot))
        return ins[0] + c * x - s * y, ins[1] + s * x + c * y

    outer = [((50, 50), 30, 2, 2, (0, 0))]
    msp.add_blockref("PAIR", (50, 50), dxfattribs={"rotation": 30, "xscale": 2, "yscale": 2, "layer": "HOLES"})
    mi = msp.add_blockref("HOLE", (0, 100), dxfattribs={"layer": "HOLES"})
    mi.grid(size=(2, 3), spacing=(10, 20))  # 2 rows 10 apart, 3 columns 20 apart

    # Expected, in the order camgen expands: model space's inserts in file order, each block's
    # own entities first, then its inserts.
    circles, paths = [], []

    def emit_hole(xf, scale, mirrored):
        circles.append([*xf(1, 1), 2.0 * scale])
        s, e = xf(7, 1), xf(5, 1)
        paths.append({"start": list(s), "closed": False, "segments": [list(e) + list(xf(6, 1)) + ["cw" if mirrored else "ccw"]]})

    for ins, rot, sx, sy, _ in outer:
        def outer_xf(x, y):
            return place(x, y, ins, rot, sx, sy)
        # PAIR's inserts: HOLE at (10, 0) rotated 90; HOLE at (-10, 0) mirrored.
        emit_hole(lambda x, y: outer_xf(*place(x, y, (10, 0), 90, 1, 1, (1, 1))), 2, False)
        emit_hole(lambda x, y: outer_xf(*place(x, y, (-10, 0), 0, -1, 1, (1, 1))), 2, True)
    for row in range(2):
        for col in range(3):
            emit_hole(lambda x, y: place(x, y, (col * 20, 100 + row * 10), 0, 1, 1, (1, 1)), 1, False)
    exp["circles"] = circles
    exp["paths"] = paths
    save(doc, "blocks", exp)


def inch():
    """A drawing in inches: camgen scales it to the job."""
    doc = new(1)
    msp = doc.modelspace()
    msp.add_circle((1, 0.5), 0.125)
    msp.add_lwpolyline([(0, 0), (2, 0), (2, 1), (0, 1)], close=True)
    save(doc, "inch", {"units": 1, "points": [], "circles": [[1, 0.5, 0.125]],
                       "paths": [poly_path([(0, 0, 0), (2, 0, 0), (2, 1, 0), (0, 1, 0)], True)]})


def plate():
    """A part: an outline with rounded corners (a polyline), a pocket (lines and arcs, drawn
    piece by piece) with an island, and holes of two diameters."""
    doc = new(4)
    for name in ("OUTLINE", "POCKET", "HOLES"):
        doc.layers.add(name)
    msp = doc.modelspace()
    b = math.tan(math.radians(90) / 4)
    msp.add_lwpolyline([(5, 0, 0), (75, 0, b), (80, 5, 0), (80, 45, b), (75, 50, 0), (5, 50, b), (0, 45, 0), (0, 5, b)],
                       format="xyb", close=True, dxfattribs={"layer": "OUTLINE"})
    for a, c in (((20, 15), (60, 15)), ((60, 35), (20, 35))):
        msp.add_line(a, c, dxfattribs={"layer": "POCKET"})
    msp.add_arc((60, 25), 10, -90, 90, dxfattribs={"layer": "POCKET"})
    msp.add_arc((20, 25), 10, 90, 270, dxfattribs={"layer": "POCKET"})
    msp.add_circle((40, 25), 4, dxfattribs={"layer": "POCKET"})
    for x, y in ((8, 8), (72, 8), (72, 42), (8, 42)):
        msp.add_circle((x, y), 2.5, dxfattribs={"layer": "HOLES"})
    msp.add_circle((40, 44), 1.6, dxfattribs={"layer": "HOLES"})
    save(doc, "plate", {"units": 4})


def bad():
    """Drawings camgen refuses, each with a clear error."""
    doc = new(4)
    msp = doc.modelspace()
    msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "CUT"})
    msp.add_line((10, 0.5), (10, 10), dxfattribs={"layer": "CUT"})   # a 0.5 gap
    msp.add_line((10, 10), (0, 10), dxfattribs={"layer": "CUT"})
    msp.add_line((0, 10), (0, 0), dxfattribs={"layer": "CUT"})
    doc.saveas(HERE / "bad-gap.dxf")
    doc = new(4)
    doc.modelspace().add_lwpolyline([(0, 0), (10, 10), (10, 0), (0, 10)], close=True)
    doc.saveas(HERE / "bad-crossing.dxf")
    doc = new(4)
    doc.modelspace().add_3dface([(0, 0, 0), (1, 0, 0), (1, 1, 0)])
    doc.saveas(HERE / "bad-entity.dxf")
    text = (HERE / "plate.dxf").read_text()
    (HERE / "bad-truncated.dxf").write_text(text[: text.index("ENTITIES") + 400])


def curves():
    """Ellipses and splines for the fit's deviation (tests/unit/test_dxf.cpp): each curve's
    definition as ezdxf wrote it (ellipse: centre, major axis, ratio, parameters; spline:
    degree, knots, control points, weights) and 21 points ezdxf puts on it, against which the
    test's own evaluation of the curve is checked first."""
    doc = new(4)
    msp = doc.modelspace()
    exp = {"units": 4, "curves": []}
    for centre, major, ratio, t0, t1 in (((0, 0), (20, 10), 0.4, 0.3, 4.0), ((60, 0), (15, 0), 0.6, 0, 2 * math.pi)):
        el = msp.add_ellipse(centre, major_axis=major, ratio=ratio, start_param=t0, end_param=t1)
        params = [t0 + (t1 - t0) * i / 20 for i in range(21)]
        exp["curves"].append({"ellipse": {"centre": list(centre), "major": list(major), "ratio": ratio, "t0": t0, "t1": t1},
                              "points": [[p.x, p.y] for p in el.construction_tool().vertices(params)]})
    for ctrl, weights, degree in (([(0, 40), (10, 60), (20, 20), (30, 70), (40, 40), (50, 45)], None, 3),
                                  ([(60, 40), (70, 60), (80, 40), (90, 60)], [1, 3, 0.5, 1], 2)):
        sp = (msp.add_open_spline(ctrl, degree=degree) if weights is None
              else msp.add_rational_spline(ctrl, weights, degree=degree))
        tool = sp.construction_tool()
        exp["curves"].append({"spline": {"degree": degree, "knots": list(sp.knots), "control": [list(c)[:2] for c in ctrl],
                                         "weights": list(weights or [1] * len(ctrl))},
                              "points": [[p.x, p.y] for p in tool.points([tool.max_t * i / 20 for i in range(21)])]})
    save(doc, "curves", exp)


def starter():
    """For camgen new --from (tests/dxf/new_from.sh): everything on layer 0, so that the
    starter job holds the outline, the pocket and its island itself; holes of 6 mm (also the
    island's diameter: written as points) and of 4 mm."""
    doc = new(4)
    msp = doc.modelspace()
    for a, b in (((0, 0), (100, 0)), ((100, 0), (100, 60)), ((100, 60), (0, 60)), ((0, 60), (0, 0))):
        msp.add_line(a, b)
    msp.add_lwpolyline([(30, 15, 0), (70, 15, 0), (70, 45, 0), (30, 45, 0)], format="xyb", close=True)
    msp.add_circle((50, 30), 3)
    for x, y in ((10, 10), (90, 10), (90, 50), (10, 50)):
        msp.add_circle((x, y), 3)
    msp.add_circle((50, 52), 2)
    msp.add_circle((50, 8), 2)
    doc.saveas(HERE / "starter.dxf")


def microns():
    """For camgen new --from: a drawing in microns ($INSUNITS 13), a 4 x 2 mm plate with a
    hole of 1 mm and a circle of 0.5 micron (a point marker: no hole to drill; its diameter
    range would have gone below 0)."""
    doc = new(13)
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (4000, 0), (4000, 2000), (0, 2000)], close=True)
    msp.add_circle((1000, 1000), 500)
    msp.add_circle((3000, 1000), 0.25)
    doc.saveas(HERE / "microns.dxf")


if __name__ == "__main__":
    starter()
    microns()
    curves()
    entities()
    ocs()
    blocks()
    inch()
    plate()
    bad()
