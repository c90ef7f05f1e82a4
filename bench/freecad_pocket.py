# FreeCAD 0.20's CAM (Path workbench) pocketing the region of a camgen pocket job, headless:
#   JOB=job.json OUTF=out.ngc [POST=linuxcnc|grbl] [OP=pocket|adaptive] freecadcmd bench/freecad_pocket.py
# (freecadcmd runs a script without its arguments, so they come in the environment).
# It reads the pocket's region from the job (bench/gen_pocket.py writes it: the outline's start and
# path of lines and arcs, the islands' likewise), builds the part a machinist would draw (a block
# with the pocket 10 mm deep in it, endDepth; the islands standing up to the top), makes a Path Job
# around it with the job's end mill (tool 1's diameter) and a PocketShape operation on the pocket's
# floor (StepOver stepOverPercent %, StepDown stepDown, offset pattern, from Z referencePlane), then
# posts the operation with FreeCAD's linuxcnc (or grbl) post into OUTF. It prints on standard error,
# one line each, for bench/run to read:
#   freecad: op=<operation> compute=<s> post=<s> cpu=<s> moves=<n> rapids=<n> feeds=<n> arcs=<n> lines=<n> length=<mm>
# compute is the wall time of the operation's recompute (FreeCAD computing its tool path), post
# that of the post's export, cpu the process's CPU time in the two (less moved by a busy
# machine); moves are the G0/G1/G2/G3 commands of the operation's path, lines those of the file,
# length the path's feed length (lines and arcs, in mm). Not counted in them: starting FreeCAD,
# building the part and the job (about 1.5 s together here). The operation is PathPocketShape
# (OP=adaptive: PathAdaptive's clearing instead, for a look at the other pocketing operation).
import json
import math
import os
import sys
import time

import FreeCAD
import Part

sys.path.append("/usr/share/freecad/Mod/Path")
import Path  # noqa: E402
import PathScripts.PathJob as PathJob  # noqa: E402
import PathScripts.PathToolBit as PathToolBit  # noqa: E402
import PathScripts.PathToolController as PathToolController  # noqa: E402

V = FreeCAD.Vector
job_file = os.environ["JOB"]
out_file = os.environ.get("OUTF", "/tmp/freecad_pocket.ngc")
post_name = os.environ.get("POST", "linuxcnc")
op_kind = os.environ.get("OP", "pocket")


def say(text):
    sys.stderr.write(text + "\n")
    sys.stderr.flush()


with open(job_file) as f:
    job_json = json.load(f)
op_json = next(o for o in job_json["operations"] if o["type"] == "pocket")
tool_json = next(t for t in job_json["tools"] if t["number"] == op_json["tool"])
top = float(op_json.get("referencePlane", 0))
depth = float(op_json["endDepth"])
bottom = top - depth


def wire(profile, z):
    """A closed profile {"start", "path"} of lines and arcs as a Part wire at height z."""
    x, y = profile["start"]
    edges = []
    for e in profile["path"]:
        if "line" in e:
            ex, ey = e["line"]
            edges.append(Part.LineSegment(V(x, y, z), V(ex, ey, z)).toShape())
        else:
            a = e["arc"]
            (ex, ey), (cx, cy) = a["end"], a["centre"]
            r = math.hypot(x - cx, y - cy)
            a0 = math.atan2(y - cy, x - cx)
            a1 = math.atan2(ey - cy, ex - cx)
            ccw = a["direction"] == "ccw"
            sweep = (a1 - a0) if ccw else (a0 - a1)
            sweep %= 2 * math.pi
            if sweep < 1e-9:  # end == start: a full circle
                circle = Part.Circle(V(cx, cy, z), V(0, 0, 1 if ccw else -1), r)
                edges.append(Part.Edge(circle))
            else:
                am = a0 + (sweep / 2 if ccw else -sweep / 2)
                mid = V(cx + r * math.cos(am), cy + r * math.sin(am), z)
                edges.append(Part.Arc(V(x, y, z), mid, V(ex, ey, z)).toShape())
        x, y = ex, ey
    return Part.Wire(edges)


doc = FreeCAD.newDocument("pocketbench")
t_build = time.time()
outline = wire({"start": op_json["start"], "path": op_json["path"]}, bottom)
holes = [wire(i, bottom) for i in op_json.get("islands", [])]
region = Part.Face([outline] + holes, "Part::FaceMakerBullseye")
if not region.isValid() or len(region.Wires) != 1 + len(holes):
    say("freecad: the region's face is not valid (%d wires)" % len(region.Wires))
    sys.exit(1)
bb = region.BoundBox
block = Part.makeBox(bb.XLength + 40, bb.YLength + 40, depth + 10, V(bb.XMin - 20, bb.YMin - 20, bottom - 10))
part = block.cut(region.extrude(V(0, 0, depth)))
model = doc.addObject("Part::Feature", "Part")
model.Shape = part
# The pocket's floor: the face at the bottom facing up.
floor = None
for i, face in enumerate(part.Faces):
    if abs(face.BoundBox.ZMin - bottom) < 1e-6 and abs(face.BoundBox.ZMax - bottom) < 1e-6:
        floor = "Face%d" % (i + 1)
if floor is None:
    say("freecad: no pocket floor found in the part")
    sys.exit(1)
doc.recompute()

job = PathJob.Create("Job", [model], None)
doc.recompute()
bit = PathToolBit.Factory.Create("EndMill", "/usr/share/freecad/Mod/Path/Tools/Shape/endmill.fcstd")
bit.Diameter = float(tool_json["diameter"])
bit.CuttingEdgeHeight = depth + 10
bit.Length = depth + 40
tc = PathToolController.Create("TC: end mill", bit, int(tool_json["number"]))
tc.SpindleSpeed = float(tool_json.get("rpm", 8000))
tc.HorizFeed = float(op_json["feed"]) / 60  # FreeCAD keeps feeds in mm/s
tc.VertFeed = float(op_json.get("plungeFeed", op_json["feed"])) / 60
# The job made a default tool controller (a 5 mm tool): ours replaces it (an operation made with
# two in the job asks the user which to take, and fails without a GUI).
for old in list(job.Tools.Group):
    job.Tools.removeObject(old)
    if getattr(old, "Tool", None) is not None:
        doc.removeObject(old.Tool.Name)
    doc.removeObject(old.Name)
job.Proxy.addToolController(tc)
doc.recompute()
say("freecad: model and job built in %.3f s" % (time.time() - t_build))

base = job.Model.Group[0]
if op_kind == "adaptive":
    import PathScripts.PathAdaptive as PathAdaptive
    op = PathAdaptive.Create("Adaptive")
    op.Base = [(base, [floor])]
    op.StepOver = int(op_json.get("stepOverPercent", 40))
    op.Side = "Inside"
    op.OperationType = "Clearing"
else:
    import PathScripts.PathPocketShape as PathPocketShape
    op = PathPocketShape.Create("Pocket")
    op.Base = [(base, [floor])]
    op.StepOver = int(op_json.get("stepOverPercent", 40))
    op.OffsetPattern = "Offset" if op_json.get("strategy", "offset") == "offset" else "ZigZag"
    op.StartAt = "Edge"
op.ToolController = tc
for prop, value in (("StartDepth", top), ("FinalDepth", bottom), ("StepDown", float(op_json.get("stepDown", depth))),
                    ("SafeHeight", top + 2), ("ClearanceHeight", float(op_json.get("retractPlane", top + 5)))):
    op.setExpression(prop, None)
    setattr(op, prop, value)

t0, c0 = time.time(), time.process_time()
doc.recompute()
compute, compute_cpu = time.time() - t0, time.process_time() - c0
if op.State and "Invalid" in op.State:
    say("freecad: the operation is invalid after recompute: %s" % (op.State,))
    sys.exit(1)

cmds = op.Path.Commands
rapids = sum(1 for c in cmds if c.Name in ("G0", "G00"))
feeds = sum(1 for c in cmds if c.Name in ("G1", "G01"))
arcs = sum(1 for c in cmds if c.Name in ("G2", "G02", "G3", "G03"))
length = 0.0
pos = V(0, 0, 0)
for c in cmds:
    if c.Name not in ("G0", "G00", "G1", "G01", "G2", "G02", "G3", "G03"):
        continue
    p = c.Parameters
    end = V(p.get("X", pos.x), p.get("Y", pos.y), p.get("Z", pos.z))
    if c.Name in ("G1", "G01"):
        length += (end - pos).Length
    elif c.Name not in ("G0", "G00"):
        centre = V(pos.x + p.get("I", 0), pos.y + p.get("J", 0), pos.z)
        r = math.hypot(pos.x - centre.x, pos.y - centre.y)
        a0 = math.atan2(pos.y - centre.y, pos.x - centre.x)
        a1 = math.atan2(end.y - centre.y, end.x - centre.x)
        sweep = (a1 - a0) if c.Name in ("G3", "G03") else (a0 - a1)
        sweep %= 2 * math.pi
        if sweep < 1e-9:
            sweep = 2 * math.pi
        length += math.hypot(r * sweep, end.z - pos.z)
    pos = end

if post_name == "grbl":
    from PathScripts.post import grbl_post as post
    args = "--no-header --no-comments --no-show-editor"
else:
    from PathScripts.post import linuxcnc_post as post
    args = "--no-header --no-comments --no-show-editor"
t0, c0 = time.time(), time.process_time()
post.export([tc, op], out_file, args)
post_time, post_cpu = time.time() - t0, time.process_time() - c0
with open(out_file) as f:
    lines = sum(1 for _ in f)
say("freecad: op=%s compute=%.3f post=%.3f cpu=%.3f moves=%d rapids=%d feeds=%d arcs=%d lines=%d length=%.0f"
    % ("PathPocketShape" if op_kind != "adaptive" else "PathAdaptive", compute, post_time, compute_cpu + post_cpu,
       rapids + feeds + arcs, rapids, feeds, arcs, lines, length))
