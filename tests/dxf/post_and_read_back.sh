#!/usr/bin/env bash
# A part from a drawing (tests/dxf/plate.json: holes, a pocket with its island and the outline
# of plate.dxf) posted for LinuxCNC, read back by camgen verify against the job and run through
# LinuxCNC's rs274 (when installed): its straight feeds and drill points must reach the
# drawing's holes (8,8) (72,8) (72,42) (8,42) and the outline's corners' tangent points.
set -euo pipefail
camgen=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$camgen" "$src/tests/dxf/plate.json" -m linuxcnc -o "$tmp/plate.ngc"
"$camgen" verify "$tmp/plate.ngc" -m linuxcnc --job "$src/tests/dxf/plate.json" | tee "$tmp/verify.txt"
grep -q "matches job" "$tmp/verify.txt"
if command -v rs274 >/dev/null; then
  printf 'T1 P1 D5\nT2 P2 D6\n' > "$tmp/tools.tbl"
  HOME="$tmp" rs274 -t "$tmp/tools.tbl" -g "$tmp/plate.ngc" </dev/null >"$tmp/rs274.txt" 2>"$tmp/rs274.err"
  # The drill cycle's points as rs274 moves to them (STRAIGHT_TRAVERSE x, y, ...).
  for hole in "8.0000, 8.0000" "72.0000, 8.0000" "72.0000, 42.0000" "8.0000, 42.0000"; do
    grep -q "STRAIGHT_TRAVERSE($hole" "$tmp/rs274.txt" || { echo "rs274 never went to the hole ($hole)"; exit 1; }
  done
  # The outline cut outside by a 6 mm tool: its bottom edge is fed along at Y -3 from X 5 to 75.
  grep -Eq "STRAIGHT_FEED\(75.0000, -3.0000|STRAIGHT_FEED\(5.0000, -3.0000" "$tmp/rs274.txt" ||
    { echo "rs274 never fed along the outline's bottom edge at Y -3"; exit 1; }
  if grep -qi "error" "$tmp/rs274.err"; then cat "$tmp/rs274.err"; exit 1; fi
fi
echo "dxf part posted, verified and read back"
