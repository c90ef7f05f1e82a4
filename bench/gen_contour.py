#!/usr/bin/env python3
"""Writes a camgen job with one contour of N line segments (a wavy closed outline about 400 mm
across, cut on the line in one pass at 3 mm: the offset is not what this measures), the shape of a CAD export
linearized to millions of segments: usage gen_contour.py N > job.json"""
import json
import math
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1000000


def point(i):
    a = 2 * math.pi * i / n
    r = 200 + 5 * math.sin(12 * a)
    return [round(200 + r * math.cos(a), 6), round(200 + r * math.sin(a), 6)]


job = {
    "name": "contour",
    "clearance": 10,
    "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 12000}],
    "operations": [{
        "type": "contour", "tool": 1, "retractPlane": 5, "referencePlane": 0, "safeDistance": 2,
        "endDepth": 3, "side": "on", "feed": 600,
        "start": point(0), "path": [{"line": point(i % n)} for i in range(1, n + 1)],
    }],
}
json.dump(job, sys.stdout)
