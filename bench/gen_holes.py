#!/usr/bin/env python3
"""Writes a camgen job with N G83-style holes (R2, Z-12, Q3, F100, from Z10), the same
holes as the FreeCAD grbl post and the LinuxCNC generator it is compared with: usage gen_holes.py N > job.json"""
import json
import sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 100000
holes = [[(i % 100) * 5.0, (i // 100) * 5.0] for i in range(n)]
job = {
    "name": "bench",
    "clearance": 10,
    "tools": [{"number": 1, "type": "drill", "diameter": 5, "tipAngle": 118, "rpm": 1500}],
    "operations": [{
        "type": "drill", "tool": 1, "cycle": "deep",
        "retractPlane": 10, "safeDistance": 2, "safeDistanceIsAbsolute": True,
        "endDepth": -12, "endDepthIsAbsolute": True, "firstDepth": 3,
        "plungingFeedrate": 100, "holes": holes,
    }],
}
json.dump(job, sys.stdout)
