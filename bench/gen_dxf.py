#!/usr/bin/python3
"""Writes the DXF benchmark drawing with ezdxf: N circles (layer HOLES, a grid 2 mm apart, two
diameters) and an LWPOLYLINE of N segments (layer OUTLINE, a closed zigzag with a bulge on
every tenth vertex). Usage: gen_dxf.py OUT.dxf [N]"""
import sys

import ezdxf

out = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 100000
doc = ezdxf.new("R2010", setup=False)
doc.header["$INSUNITS"] = 4
doc.layers.add("HOLES")
doc.layers.add("OUTLINE")
msp = doc.modelspace()
side = int(n ** 0.5) + 1
for i in range(n):
    msp.add_circle((10 + 2 * (i % side), 10 + 2 * (i // side)), 0.5 if i % 2 else 0.4, dxfattribs={"layer": "HOLES"})
# A closed outline of n segments: n - 3 along the bottom (a shallow zigzag), then up, back, down.
width = 2 * side + 20
pts = []
m = n - 3
for i in range(m):
    pts.append((width * i / m, -1 - 0.5 * (i % 2), 0.2 if i % 10 == 0 else 0))
pts += [(width, -1, 0), (width, 2 * side + 20, 0), (0, 2 * side + 20, 0)]
msp.add_lwpolyline(pts, format="xyb", close=True, dxfattribs={"layer": "OUTLINE"})
doc.saveas(out)
