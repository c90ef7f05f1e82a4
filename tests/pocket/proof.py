#!/usr/bin/python3
"""The proof of the pocket and face operations (issue 26): coverage and clearance measured on
the tool path LinuxCNC's interpreter makes of camgen's programs, with shapely (GEOS), nothing of
camgen's geometry.

Usage: proof.py CAMGEN_ORACLE WORK_DIR   (the oracle's output in WORK_DIR/oracle.txt, its moves in
                                         WORK_DIR/moves.jsonl, measured as it writes them)
       proof.py --moves MOVES_FILE      (the geometry of a file the oracle wrote before)

It runs `CAMGEN_ORACLE -tc='pocket proof*'` (tests/oracle/test_pocket_proof.cpp: the pocket and
face samples and seeded random jobs, each refused with an error naming its operation or posted
for linuxcnc and fanuc, both programs run through `rs274 -g` to PROGRAM_END and compared with
camgen's read-back within 0.001 mm) with CAMGEN_POCKET_PROOF=WORK_DIR/moves.jsonl, where that
test writes each operation's job and the moves rs274 made for it in the linuxcnc program. Then,
for each operation, with the arcs of the moves and of the job's loops cut into chords at most
CHORD off them:

Pockets (R: the outline less the islands, r: the tool radius, s: stockToLeave, at a roughing
level s + finishing.radialStock):
  - coverage: at every depth level, the union of the tool's disks along the moves at that level
    (the path buffered by r) covers R opened by the tool (R shrunk by r + s, grown by r: all a
    tool of radius r leaving s can reach), but at most UNCOVERED mm^2 per mm of wall (R's
    perimeter);
  - no gouge: every tool-centre point below the stock top stays inside R and at least r + s
    (final) from its walls and islands, less GOUGE_DISTANCE; the roughing levels and entries
    keep r + s + radialStock;
    and the swept area at each level lies inside R shrunk by that level's stock, but for at
    most GOUGE_AREA mm^2 per mm of wall;
  - the floor: the lowest point is the end depth (axialStock above it before the floor pass);
  - rapids below the stock top only straight up out of the cut.
Faces (A: the area):
  - coverage: at every depth level the swept disks cover A, but at most UNCOVERED per mm of
    its perimeter; the lowest point is the end depth;
  - every descent below the stock top happens beside A, at least the tool radius plus the
    overhang from it (no plunge over the area); rapids below the top only straight up.

Any failure prints the operation's job (JSON) to reproduce it. The counts, the largest figures
and the run time are printed. Needs python3-shapely (Debian's, hence /usr/bin/python3)."""

import json
import math
import os
import subprocess
import sys
import time
from multiprocessing import Pool

try:
    from shapely.geometry import LineString, MultiLineString, MultiPoint, Point, Polygon
    from shapely.ops import unary_union
except ImportError:
    print("python3-shapely is needed (scripts/install-deps --tests installs it; run Debian's /usr/bin/python3)")
    sys.exit(1)

CHORD = 0.0005  # mm: the largest distance of a chord from its arc (paths and loops)
QUAD = 32  # shapely's buffer segments per quarter circle (a disk's polygon is at most 0.0011 mm inside it for r = 4)
UNCOVERED = 0.01  # mm^2 per mm of wall: what may stay uncovered (the proof's bound)
# The program's coordinates are rounded to 0.0001 mm (linuxcnc) and rs274 prints 4 decimals;
# the chords lie up to CHORD inside their arcs, the loops' chords as much: 0.002 mm covers them.
GOUGE_DISTANCE = 0.002  # mm
GOUGE_AREA = 0.001  # mm^2 per mm of wall: a band 0.001 mm wide
LEVEL = 1e-4  # mm: two Z this close are one level
LEVEL_MOVE = 0.05  # mm: the shortest horizontal move that makes a level (a ramp of 1 degree drops 0.0009 mm on it)
# Every CROSS_CHECK-th record's swept area at the end depth is also made segment by segment (slow)
# and must agree with the fast one within CROSS_TOLERANCE mm^2 per mm of wall.
CROSS_CHECK = 20
CROSS_TOLERANCE = 5e-4


def arc_points(p0, p1, c, ccw, turns, chord):
    """Points after p0 up to p1 along the arc about c (turns: the turns begun, >= 1)."""
    r = math.hypot(p0[0] - c[0], p0[1] - c[1])
    a0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
    a1 = math.atan2(p1[1] - c[1], p1[0] - c[0])
    sweep = (a1 - a0) if ccw else (a0 - a1)
    while sweep <= 1e-12:
        sweep += 2 * math.pi
    while sweep > 2 * math.pi + 1e-12:
        sweep -= 2 * math.pi
    sweep += 2 * math.pi * (turns - 1)
    step = 2 * math.acos(1 - min(chord, r) / r) if r > chord else math.pi / 2
    n = max(2, math.ceil(sweep / step))
    sign = 1 if ccw else -1
    out = []
    for k in range(1, n):
        a = a0 + sign * sweep * k / n
        out.append((c[0] + r * math.cos(a), c[1] + r * math.sin(a)))
    out.append((p1[0], p1[1]))
    return out


def loop_points(loop):
    """A job's closed loop (start, path of lines and arcs) as a polygon's points."""
    at = tuple(loop["start"])
    pts = [at]
    for e in loop["path"]:
        if "line" in e:
            to = tuple(e["line"])
            pts.append(to)
        else:
            a = e["arc"]
            to = tuple(a["end"])
            pts.extend(arc_points(at, to, a["centre"], a["direction"] == "ccw", 1, CHORD / 2))
        at = to
    return pts[:-1]


def region_of(op):
    if "rectangle" in op:
        (x0, y0), (x1, y1) = op["rectangle"]["corner"], op["rectangle"]["oppositeCorner"]
        return Polygon([(x0, y0), (x1, y0), (x1, y1), (x0, y1)]).buffer(0)
    holes = [loop_points(i) for i in op.get("islands", [])]
    return Polygon(loop_points(op), holes)


class Move:
    __slots__ = ("kind", "pts", "z0", "z1")

    def __init__(self, kind, pts, z0, z1):
        self.kind, self.pts, self.z0, self.z1 = kind, pts, z0, z1


def moves_of(record):
    """The moves as polylines (XY points, the Z at their ends)."""
    at = record["start"]
    out = []
    for m in record["moves"]:
        to = m[1:4]
        if m[0] == "a":
            rot = m[6]
            pts = [(at[0], at[1])] + arc_points(at, to, (m[4], m[5]), rot > 0, abs(rot), CHORD)
        else:
            pts = [(at[0], at[1]), (to[0], to[1])]
        out.append(Move(m[0], pts, at[2], to[2]))
        at = to
    return out


def line_of(pts):
    if len(pts) == 2 and pts[0] == pts[1]:
        return Point(pts[0])
    return LineString(pts)


def swept(moves, r, quad=QUAD):
    """The area the tool's disk sweeps along the moves: the union of each move's buffer by r
    (GEOS's buffer; a circle's polygon has its vertices on the circle: at most the true area).
    Each move alone: a line, or an arc in chords, never crosses itself (GEOS's buffer of a long
    polyline that overlaps itself, a whole level chained, loses pieces of the area)."""
    pieces = [line_of(m.pts).buffer(r, resolution=quad) for m in moves]
    return unary_union(pieces) if pieces else Polygon()


def swept_by_segments(moves, r):
    """The same area as the union of each segment's buffer (slower): a line of two points has
    nothing to simplify before GEOS buffers it."""
    pieces = []
    for m in moves:
        pieces += [line_of([a, b]).buffer(r, resolution=QUAD) for a, b in zip(m.pts, m.pts[1:]) if a != b]
        if all(p == m.pts[0] for p in m.pts):
            pieces.append(Point(m.pts[0]).buffer(r, resolution=QUAD))
    return unary_union(pieces) if pieces else Polygon()


def levels_of(moves, top):
    """The Z of the horizontal feed moves below the top, each once, top down (moves of at least
    LEVEL_MOVE: a ramp's step over a crumb of a path, 0.001 mm long, is level once rounded)."""
    zs = []
    for m in moves:
        length = sum(math.dist(a, b) for a, b in zip(m.pts, m.pts[1:]))
        if m.kind != "t" and abs(m.z0 - m.z1) < LEVEL and m.z0 < top - LEVEL and length >= LEVEL_MOVE:
            if not any(abs(m.z0 - z) < LEVEL for z in zs):
                zs.append(m.z0)
    return sorted(zs, reverse=True)


def at_level(moves, z):
    return [m for m in moves if m.kind != "t" and abs(m.z0 - z) < LEVEL and abs(m.z1 - z) < LEVEL]


def common_checks(record, moves, top, bottom, fail):
    for m in moves:
        # A rapid below the top only goes straight up out of the cut.
        straight_up = m.pts[0] == m.pts[-1] and m.z1 > m.z0
        if m.kind == "t" and min(m.z0, m.z1) < top - 1e-6 and not straight_up:
            fail(f"a rapid below the stock top Z{top:g}: from ({m.pts[0][0]:.4f}, {m.pts[0][1]:.4f}, {m.z0:.4f}) "
                 f"to ({m.pts[-1][0]:.4f}, {m.pts[-1][1]:.4f}, {m.z1:.4f})")
            break
    lowest = min(m.z1 for m in moves)  # (the first move starts where the operation before left the tool)
    if abs(lowest - bottom) > 0.0011:
        fail(f"the lowest point is Z{lowest:.4f}, the end depth Z{bottom:.4f}")


def check_pocket(record, moves, cross=False):
    job = record["job"]
    op = job["operations"][0]
    tool = next(t for t in job["tools"] if t["number"] == op["tool"])
    r = tool["diameter"] / 2
    s = op.get("stockToLeave", 0.0)
    fin = op.get("finishing")
    radial = fin.get("radialStock", 0.0) if fin else 0.0
    axial = fin.get("axialStock", 0.0) if fin else 0.0
    top = op.get("referencePlane", 0.0)
    bottom = top - op["endDepth"]
    region = region_of(op)
    wall = region.length
    problems = []
    fail = problems.append
    if not region.is_valid:
        fail("the job's region is not a valid polygon here")
        return problems, {}
    common_checks(record, moves, top, bottom, fail)
    boundary = region.boundary
    figures = {"wall": wall, "uncovered": 0.0, "gouge_area": 0.0, "margin": math.inf, "rough_margin": math.inf}
    # Clearance of every tool-centre point below the top.
    below = [m for m in moves if m.kind != "t" and min(m.z0, m.z1) < top - 1e-6]
    if not below:
        fail("no move below the stock top")
        return problems, figures
    paths = MultiLineString([m.pts if m.pts[0] != m.pts[-1] or len(m.pts) > 2 else [m.pts[0], m.pts[0]] for m in below])
    if not region.contains(paths):
        outside = paths.difference(region)
        p = outside.representative_point() if not outside.is_empty else None
        fail("a tool centre leaves the pocket" + (f" near ({p.x:.4f}, {p.y:.4f})" if p else ""))
    d = boundary.distance(paths)
    figures["margin"] = d - (r + s)
    if d < r + s - GOUGE_DISTANCE:
        fail(f"a tool centre comes {d:.4f} mm from a wall, it must keep {r + s:.4f} (radius + stockToLeave)")
    # The roughing (entries, levels above the floor pass) keeps the radial stock too: all but the
    # moves at the end depth and the descents straight to it (the finishing pass goes down where
    # its lead-in starts), when the finishing runs at the end depth only (no finishing stepDown).
    if fin and radial > 0 and "stepDown" not in fin:
        def finishing(m):
            return abs(m.z1 - bottom) < LEVEL and (abs(m.z0 - bottom) < LEVEL or (m.kind == "f" and m.pts[0] == m.pts[-1]))
        rough = [m for m in below if not finishing(m)]
        if rough:
            dr = boundary.distance(MultiLineString([m.pts for m in rough]))
            figures["rough_margin"] = dr - (r + s + radial)
            if dr < r + s + radial - GOUGE_DISTANCE:
                worst = min(rough, key=lambda m: boundary.distance(line_of(m.pts)))
                fail(f"a roughing move or descent comes {dr:.4f} mm from a wall, it must keep {r + s + radial:.4f} "
                     f"(radius + stockToLeave + radialStock): from ({worst.pts[0][0]:.4f}, {worst.pts[0][1]:.4f}, {worst.z0:.4f}) "
                     f"to ({worst.pts[-1][0]:.4f}, {worst.pts[-1][1]:.4f}, {worst.z1:.4f})")
    levels = levels_of(moves, top)
    if fin and axial > 0:
        rough_levels = [z for z in levels if z > bottom + LEVEL]
        if not rough_levels or abs(min(rough_levels) - (bottom + axial)) > 0.0011:
            fail(f"the last roughing level is not axialStock {axial:g} above the end depth: levels {levels}")
    for z in levels:
        stock = s if abs(z - bottom) < LEVEL else s + radial
        cut = swept(at_level(moves, z), r)
        target = region.buffer(-(r + stock), resolution=QUAD)
        if not target.is_empty:
            target = target.buffer(r, resolution=QUAD)
        missed = target.difference(cut)
        if cross and abs(z - bottom) < LEVEL:
            # The fast union of the moves' buffers against the union of every segment's.
            other = swept_by_segments(at_level(moves, z), r)
            figures["cross"] = cut.symmetric_difference(other).area / wall
            if figures["cross"] > CROSS_TOLERANCE:
                fail(f"the swept area by moves and by segments differ by {figures['cross']:.6f} mm^2 per mm of wall")
        figures["uncovered"] = max(figures["uncovered"], missed.area / wall)
        if missed.area > UNCOVERED * wall:
            p = missed.representative_point()
            fail(f"at Z{z:.4f} {missed.area:.4f} mm^2 that the tool can reach stays uncut ({missed.area / wall:.5f} per mm of wall, "
                 f"at most {UNCOVERED}), e.g. near ({p.x:.3f}, {p.y:.3f})")
        allowed = region.buffer(-stock, resolution=QUAD) if stock > 0 else region
        gouge = cut.difference(allowed)
        figures["gouge_area"] = max(figures["gouge_area"], gouge.area / wall)
        if gouge.area > GOUGE_AREA * wall:
            p = gouge.representative_point()
            fail(f"at Z{z:.4f} the tool cuts {gouge.area:.4f} mm^2 of what stays (stock {stock:g}), e.g. near ({p.x:.3f}, {p.y:.3f})")
    if not levels or abs(levels[-1] - bottom) > LEVEL:
        fail(f"no cut at the end depth Z{bottom:g}")
    return problems, figures


def check_face(record, moves):
    job = record["job"]
    op = job["operations"][0]
    tool = next(t for t in job["tools"] if t["number"] == op["tool"])
    r = tool["diameter"] / 2
    overhang = op.get("overhang", 2.0)
    top = op.get("referencePlane", 0.0)
    bottom = top - op["endDepth"]
    area = region_of(op)
    wall = area.length
    problems = []
    fail = problems.append
    common_checks(record, moves, top, bottom, fail)
    figures = {"wall": wall, "uncovered": 0.0, "descent": math.inf}
    for m in moves:
        if m.z1 < m.z0 - 1e-9 and m.z1 < top - 1e-6:
            d = area.distance(line_of(m.pts))
            figures["descent"] = min(figures["descent"], d - (r + overhang))
            if d < r + overhang - GOUGE_DISTANCE:
                fail(f"the tool goes down to Z{m.z1:.4f} {d:.4f} mm from the area, within its radius and the overhang "
                     f"{r + overhang:.4f}: at ({m.pts[-1][0]:.4f}, {m.pts[-1][1]:.4f})")
                break
    levels = levels_of(moves, top)
    if not levels or abs(levels[-1] - bottom) > LEVEL:
        fail(f"no cut at the end depth Z{bottom:g}")
    for z in levels:
        missed = area.difference(swept(at_level(moves, z), r))
        figures["uncovered"] = max(figures["uncovered"], missed.area / wall)
        if missed.area > UNCOVERED * wall:
            p = missed.representative_point()
            fail(f"at Z{z:.4f} {missed.area:.4f} mm^2 of the area stays uncut, e.g. near ({p.x:.3f}, {p.y:.3f})")
    return problems, figures


def check(numbered_line):
    number, line = numbered_line
    record = json.loads(line)
    if record["kind"] == "refused":
        return number, record["kind"], record["name"], [], {}, None
    moves = moves_of(record)
    try:
        if record["kind"] == "pocket":
            problems, figures = check_pocket(record, moves, number % CROSS_CHECK == 0)
        else:
            problems, figures = check_face(record, moves)
    except Exception as e:  # a failure of the check itself is a failure too, with the job
        problems, figures = [f"the check failed: {type(e).__name__}: {e}"], {}
    return number, record["kind"], record["name"], problems, figures, json.dumps(record["job"]) if problems else None


def follow(path, process, ended):
    """The lines of the file the running oracle writes, as it writes them, to its end (the
    time of which goes to ended["at"])."""
    while not os.path.exists(path):
        if process.poll() is not None:
            ended["at"] = time.monotonic()
            return
        time.sleep(0.05)
    with open(path) as f:
        pending = ""
        while True:
            done = process.poll() is not None  # asked before reading: all it wrote is there then
            pending += f.read()
            *lines, pending = pending.split("\n")
            yield from (line + "\n" for line in lines)
            if done:
                ended["at"] = time.monotonic()
                return
            time.sleep(0.05)


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    began = time.monotonic()
    oracle_failed, oracle_seconds = False, 0.0
    if sys.argv[1] == "--moves":
        # The geometry alone, of a file the oracle wrote before.
        with open(sys.argv[2]) as f:
            lines = f.readlines()
        with Pool(2) as pool:
            results = pool.map(check, list(enumerate(lines)), chunksize=4)
    else:
        # The oracle on one core, the geometry of what it has written so far on the other.
        oracle, work = sys.argv[1], sys.argv[2]
        os.makedirs(work, exist_ok=True)
        moves_file = os.path.join(work, "moves.jsonl")
        if os.path.exists(moves_file):
            os.remove(moves_file)
        env = dict(os.environ, CAMGEN_POCKET_PROOF=moves_file)
        with open(os.path.join(work, "oracle.txt"), "w+") as out:
            process = subprocess.Popen([oracle, "-tc=pocket proof*"], env=env, stdout=out, stderr=subprocess.STDOUT, text=True)
            ended = {}
            with Pool(2) as pool:
                results = list(pool.imap_unordered(check, enumerate(follow(moves_file, process, ended)), chunksize=2))
            process.wait()
            oracle_seconds = ended.get("at", time.monotonic()) - began
            out.seek(0)
            print(out.read())
        if process.returncode != 0:
            oracle_failed = True
            # The geometry is checked all the same: its failures may tell more.
            print(f"FAILED: {oracle} -tc='pocket proof*' exit {process.returncode}")
    results.sort(key=lambda r: r[0])
    results = [r[1:] for r in results]
    geometry_seconds = time.monotonic() - began
    counts = {"pocket": 0, "face": 0, "refused": 0}
    failed = 0
    worst = {"pocket uncovered": (0.0, ""), "pocket gouge area": (0.0, ""), "face uncovered": (0.0, "")}
    margins = {"pocket clearance margin": (math.inf, ""), "pocket roughing margin": (math.inf, ""), "face descent margin": (math.inf, "")}
    for kind, name, problems, figures, job in results:
        counts[kind] += 1
        if problems:
            failed += 1
            print(f"FAILED: {kind} {name}:")
            for p in problems:
                print(f"  {p}")
            print(f"  the job: {job}")
        if kind == "pocket" and figures:
            for key, fig in (("pocket uncovered", "uncovered"), ("pocket gouge area", "gouge_area")):
                if figures[fig] >= worst[key][0]:
                    worst[key] = (figures[fig], name)
            for key, fig in (("pocket clearance margin", "margin"), ("pocket roughing margin", "rough_margin")):
                if figures[fig] < margins[key][0]:
                    margins[key] = (figures[fig], name)
        if kind == "face" and figures:
            if figures["uncovered"] >= worst["face uncovered"][0]:
                worst["face uncovered"] = (figures["uncovered"], name)
            if figures["descent"] < margins["face descent margin"][0]:
                margins["face descent margin"] = (figures["descent"], name)
    print(f"pocket proof, geometry: {counts['pocket']} pockets and {counts['face']} faces checked ({counts['refused']} random jobs "
          f"refused by camgen, listed by the oracle above); {failed} failed")
    for key, (value, name) in worst.items():
        print(f"  largest {key}: {value:.6f} mm^2 per mm of wall ({name})")
    for key, (value, name) in margins.items():
        print(f"  smallest {key}: {value:+.4f} mm ({name})")
    crosses = [f["cross"] for kind, _, _, f, _ in results if f and "cross" in f]
    print(f"  swept area by moves and by segments: {len(crosses)} pockets compared, largest difference "
          f"{max(crosses, default=0.0):.7f} mm^2 per mm of wall (at most {CROSS_TOLERANCE})")
    print(f"  bounds: uncovered <= {UNCOVERED} mm^2/mm, gouge area <= {GOUGE_AREA} mm^2/mm, clearance >= -{GOUGE_DISTANCE} mm")
    print(f"  time: oracle (posting, rs274, read-back) {oracle_seconds:.1f} s, the geometry alongside and after it: {geometry_seconds:.1f} s in all")
    if counts["pocket"] < 2 or counts["face"] < 2:
        print("FAILED: too few operations checked")
        return 1
    return 1 if failed or oracle_failed else 0


if __name__ == "__main__":
    sys.exit(main())
