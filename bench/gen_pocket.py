#!/usr/bin/env python3
"""Writes a camgen job with one pocket (issue 26's speed target): an outline of W x H mm with R10
corners (lines and arcs, drawn counter-clockwise from [10, 0]) around N islands (a grid of circles
and rounded rectangles in turn, their sizes varied deterministically, well apart from each other
and from the walls), a 6 mm end mill, 5 depth passes of 2 mm, offset strategy at 40 % stepover.

usage: gen_pocket.py [--width W] [--height H] [--islands N] [--scale K]
                     [--svg FILE] [--json-region FILE] > job.json

--scale K multiplies every length of the region by sqrt(K) (its area by K; the tool, the depths
and the feeds stay): the linearity check posts K = 1 and K = 10. --svg FILE also draws the region
(to look at it), --json-region FILE also writes the region alone: {"outline": {"start", "path"},
"islands": [...]} in the job's coordinates. Standard library only."""
import argparse
import json
import math
import sys


def num(v):
    """A coordinate rounded to 6 decimals, an integer when whole (so never -0)."""
    r = round(v, 6)
    return int(r) if r == int(r) else r


def pt(x, y):
    return [num(x), num(y)]


def rounded_rect(x0, y0, x1, y1, r):
    """A closed counter-clockwise profile of the rectangle [x0, x1] x [y0, y1] with corners of
    radius r: {"start", "path"}."""
    path = [
        {"line": pt(x1 - r, y0)},
        {"arc": {"end": pt(x1, y0 + r), "centre": pt(x1 - r, y0 + r), "direction": "ccw"}},
        {"line": pt(x1, y1 - r)},
        {"arc": {"end": pt(x1 - r, y1), "centre": pt(x1 - r, y1 - r), "direction": "ccw"}},
        {"line": pt(x0 + r, y1)},
        {"arc": {"end": pt(x0, y1 - r), "centre": pt(x0 + r, y1 - r), "direction": "ccw"}},
        {"line": pt(x0, y0 + r)},
        {"arc": {"end": pt(x0 + r, y0), "centre": pt(x0 + r, y0 + r), "direction": "ccw"}},
    ]
    return {"start": pt(x0 + r, y0), "path": path}


def circle(cx, cy, r):
    """A full circle: one counter-clockwise arc whose end is its start."""
    start = pt(cx + r, cy)
    return {"start": start, "path": [{"arc": {"end": start, "centre": pt(cx, cy), "direction": "ccw"}}]}


def region(width, height, corner, count):
    """The outline and the islands: count islands on a grid of cols x rows cells (5 x 4 for 20 in
    300 x 200), each island centred in its cell and at most 0.6 of the cell's smaller side across,
    so that the gaps between islands are at least 0.4 of it and those to the walls 0.2 (20 mm and
    10 mm at 300 x 200: a 6 mm tool passes everywhere)."""
    outline = rounded_rect(0, 0, width, height, corner)
    islands = []
    if count > 0:
        cols = max(1, round(math.sqrt(count * width / height)))
        rows = math.ceil(count / cols)
        cw, ch = width / cols, height / rows
        m = min(cw, ch)
        for i in range(count):
            row, col = divmod(i, cols)
            cx, cy = (col + 0.5) * cw, (row + 0.5) * ch
            f = 0.18 + 0.03 * ((i * 7) % 5)  # half-size 0.18 .. 0.30 of the cell's smaller side
            if (row + col) % 2 == 0:
                islands.append(circle(cx, cy, f * m))
            else:
                hw = f * m
                hh = f * m * (0.55 + 0.15 * (i % 3))
                r = hh * (0.25 + 0.1 * (i % 4))
                islands.append(rounded_rect(cx - hw, cy - hh, cx + hw, cy + hh, r))
    return outline, islands


def svg(outline, islands, width, height):
    def d(profile):
        x, y = profile["start"]
        out = ["M %g %g" % (x, height - y)]
        for e in profile["path"]:
            if "line" in e:
                x, y = e["line"]
                out.append("L %g %g" % (x, height - y))
            else:
                a = e["arc"]
                (ex, ey), (cx, cy) = a["end"], a["centre"]
                r = math.hypot(x - cx, y - cy)
                sweep = 0 if a["direction"] == "ccw" else 1  # y flips in SVG
                if [ex, ey] == [x, y]:  # a full circle: two halves
                    mx, my = 2 * cx - x, 2 * cy - y
                    out.append("A %g %g 0 0 %d %g %g" % (r, r, sweep, mx, height - my))
                out.append("A %g %g 0 0 %d %g %g" % (r, r, sweep, ex, height - ey))
                x, y = ex, ey
        return " ".join(out) + " Z"

    paths = " ".join(d(p) for p in [outline] + islands)
    return ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="-5 -5 %g %g" width="%g" height="%g">\n'
            '<path d="%s" fill="#cde" fill-rule="evenodd" stroke="#000" stroke-width="0.5"/>\n</svg>\n'
            % (width + 10, height + 10, width + 10, height + 10, paths))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--width", type=float, default=300)
    p.add_argument("--height", type=float, default=200)
    p.add_argument("--islands", type=int, default=20)
    p.add_argument("--scale", type=float, default=1, help="area factor K: lengths x sqrt(K)")
    p.add_argument("--svg", help="also draw the region into this SVG file")
    p.add_argument("--json-region", help="also write the region alone into this JSON file")
    a = p.parse_args()
    if a.width <= 0 or a.height <= 0 or a.islands < 0 or a.scale <= 0:
        p.error("width, height and scale must be > 0, islands >= 0")
    s = math.sqrt(a.scale)
    width, height = a.width * s, a.height * s
    outline, islands = region(width, height, 10 * s, a.islands)
    pocket = {
        "type": "pocket", "tool": 1,
        "comment": "pocket %g x %g, R%g corners, %d islands" % (num(width), num(height), num(10 * s), len(islands)),
        "referencePlane": 0, "retractPlane": 5, "endDepth": 10, "stepDown": 2,
        "start": outline["start"], "path": outline["path"], "islands": islands,
        "strategy": "offset", "stepOverPercent": 40, "feed": 800, "plungeFeed": 300,
    }
    job = {
        "name": "pocket",
        "units": "mm",
        "clearance": 15,
        "tools": [{"number": 1, "type": "end-mill", "diameter": 6, "rpm": 8000, "comment": "6 mm end mill"}],
        "operations": [pocket],
    }
    json.dump(job, sys.stdout)
    sys.stdout.write("\n")
    if a.svg:
        with open(a.svg, "w") as f:
            f.write(svg(outline, islands, width, height))
    if a.json_region:
        with open(a.json_region, "w") as f:
            json.dump({"outline": outline, "islands": islands}, f)
            f.write("\n")


main()
