#!/usr/bin/env bash
# camgen dxf-info and camgen new --from: the starter jobs of plate.dxf (operations that name
# the drawing by layer and diameter) and starter.dxf (everything on one layer: the outline,
# the pocket with its island and the holes the island's diameter shares are written into the
# job) post as written on wabeco and linuxcnc, camgen verify finds the linuxcnc program to be
# its job, and LinuxCNC's rs274 (when installed) runs it to its end and drills the holes.
set -euo pipefail
camgen=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$camgen" dxf-info "$src/tests/dxf/plate.dxf" >"$tmp/info.txt"
grep -q "^  HOLES  *5  CIRCLE 5$" "$tmp/info.txt" || fail "dxf-info: layer HOLES with 5 circles"
grep -q "^  layer OUTLINE: 8 segments, X 0 .. 80  Y 0 .. 50" "$tmp/info.txt" || fail "dxf-info: the outline's extent"
grep -q "^  diameter 5: 4 circles on layer HOLES$" "$tmp/info.txt" || fail "dxf-info: the 5 mm circles"
grep -q "^open profiles: 0$" "$tmp/info.txt" || fail "dxf-info: no open profiles"
"$camgen" dxf-info "$src/tests/dxf/entities.dxf" | grep -q "^open profiles: 4$" || fail "dxf-info: entities.dxf has 4 open profiles"

for drawing in plate starter; do
  mkdir -p "$tmp/$drawing"
  "$camgen" new --from "$src/tests/dxf/$drawing.dxf" --machine wabeco -o "$tmp/$drawing/job.json" 2>"$tmp/$drawing/notes.txt"
  for machine in wabeco linuxcnc; do
    "$camgen" "$tmp/$drawing/job.json" -m $machine -o "$tmp/$drawing/$machine.nc" -q || fail "$drawing: the starter job does not post on $machine"
  done
  "$camgen" verify "$tmp/$drawing/linuxcnc.nc" -m linuxcnc --job "$tmp/$drawing/job.json" >"$tmp/$drawing/verify.txt"
  grep -q "matches job" "$tmp/$drawing/verify.txt" || fail "$drawing: verify"
done
# plate.dxf: the operations name the drawing.
grep -q '"layer": "POCKET"' "$tmp/plate/job.json" || fail "plate: the pocket by its layer"
grep -q '"layer": "OUTLINE"' "$tmp/plate/job.json" || fail "plate: the contour by its layer"
[ "$(grep -c '"drawing"' "$tmp/plate/job.json")" = 2 ] || fail "plate: two drill operations from the drawing (3.2 and 5 mm)"
# starter.dxf: one layer for everything, so the geometry is written into the job.
grep -q '"islands"' "$tmp/starter/job.json" || fail "starter: the pocket's island"
grep -q '"holes"' "$tmp/starter/job.json" || fail "starter: the 6 mm holes as points (the island is 6 mm too)"
if command -v rs274 >/dev/null; then
  for drawing in plate starter; do
    HOME="$tmp" rs274 -g "$tmp/$drawing/linuxcnc.nc" </dev/null >"$tmp/$drawing/rs274.txt" 2>"$tmp/$drawing/rs274.err" || fail "$drawing: rs274"
    grep -q "PROGRAM_END" "$tmp/$drawing/rs274.txt" || fail "$drawing: rs274 did not reach the program's end"
    if grep -qi "error" "$tmp/$drawing/rs274.err"; then cat "$tmp/$drawing/rs274.err"; exit 1; fi
  done
  for hole in "8.0000, 8.0000" "72.0000, 42.0000" "40.0000, 44.0000"; do
    grep -q "STRAIGHT_TRAVERSE($hole" "$tmp/plate/rs274.txt" || fail "rs274 never went to plate's hole ($hole)"
  done
  for hole in "10.0000, 10.0000" "90.0000, 50.0000" "50.0000, 8.0000"; do
    grep -q "STRAIGHT_TRAVERSE($hole" "$tmp/starter/rs274.txt" || fail "rs274 never went to starter's hole ($hole)"
  done
  grep -q "STRAIGHT_TRAVERSE(50.0000, 30.0000" "$tmp/starter/rs274.txt" && fail "starter: the island was drilled"
fi
# A drawing in microns: the 1 mm hole is drilled, the 0.5 micron circle left out with a note (its
# diameter range [d - 0.001, d + 0.001] went below 0, and the starter job did not read).
"$camgen" new --from "$src/tests/dxf/microns.dxf" -o "$tmp/microns.json" 2>"$tmp/microns.err" || { cat "$tmp/microns.err"; fail "microns.dxf: no starter job"; }
grep -q "1 circle of diameter 0.0005 mm left out: too small to drill" "$tmp/microns.err" || fail "microns.dxf: the note on the tiny circle"
[ "$(grep -c '"type": "drill"' "$tmp/microns.json")" = 2 ] || fail "microns.dxf: one drill (tool and operation) for the 1 mm hole"
"$camgen" "$tmp/microns.json" -m linuxcnc -q -o "$tmp/microns.nc" || fail "microns.dxf: the starter job does not post"
# Nothing to machine: an error, nothing written.
if "$camgen" new --from "$src/tests/dxf/bad-gap.dxf" -o "$tmp/none.json" 2>"$tmp/none.err"; then fail "bad-gap.dxf made a job"; fi
grep -q "holds nothing a starter job machines" "$tmp/none.err" || fail "bad-gap.dxf: the message"
[ ! -e "$tmp/none.json" ] || fail "bad-gap.dxf: a file was written"
echo "dxf-info and new --from checked"
