# Writes tests/dxf/freecad.dxf with FreeCAD's own DXF exporter (importDXF.export, an
# independent writer) and tests/dxf/freecad.expected.json with the geometry FreeCAD was given,
# in the format of make_drawings.py. Run: freecadcmd tests/dxf/make_freecad.py (FreeCAD 0.20;
# the files are committed, so the tests do not need FreeCAD).
import json
import math
import os

import FreeCAD
import Part
import importDXF
from FreeCAD import Vector as V

HERE = os.path.dirname(os.path.abspath(__file__))
doc = FreeCAD.newDocument("camgen")
objs = []
exp = {"units": 4, "points": [], "circles": [], "paths": []}


def add(shape, name):
    o = doc.addObject("Part::Feature", name)
    o.Shape = shape
    objs.append(o)


add(Part.makeLine(V(0, 0, 0), V(40.5, 0, 0)), "line")
exp["paths"].append({"start": [0, 0], "closed": False, "segments": [[40.5, 0]]})
add(Part.ArcOfCircle(Part.Circle(V(40.5, 10, 0), V(0, 0, 1), 10), -math.pi / 2, math.pi / 2).toShape(), "arc")
exp["paths"].append({"start": [40.5, 0], "closed": False, "segments": [[40.5, 20, 40.5, 10, "ccw"]]})
add(Part.makeCircle(3.3, V(12.25, 7.75, 0)), "circle")
exp["circles"].append([12.25, 7.75, 3.3])
add(Part.makeCircle(2.5, V(-8.125, 30.0625, 0)), "circle2")
exp["circles"].append([-8.125, 30.0625, 2.5])
add(Part.ArcOfCircle(Part.Circle(V(70, 30, 0), V(0, 0, 1), 6.5), math.radians(30), math.radians(200)).toShape(), "arc2")
exp["paths"].append({"start": [70 + 6.5 * math.cos(math.radians(30)), 30 + 6.5 * math.sin(math.radians(30))], "closed": False,
                     "segments": [[70 + 6.5 * math.cos(math.radians(200)), 30 + 6.5 * math.sin(math.radians(200)), 70, 30, "ccw"]]})
doc.recompute()
importDXF.export(objs, os.path.join(HERE, "freecad.dxf"))
with open(os.path.join(HERE, "freecad.expected.json"), "w") as f:
    f.write(json.dumps(exp, indent=1) + "\n")
