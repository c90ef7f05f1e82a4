#!/usr/bin/env bash
# bench/run dxf: camgen's DXF reader against ezdxf (issue 28): a drawing of N circles and an
# N-segment polyline (bench/gen_dxf.py, written by ezdxf), read by `camgen dxf-info` (read,
# every circle grouped by diameter, the polyline chained and measured: the whole process) and
# by ezdxf.readfile (the call alone, timed inside python, and the whole python process), in
# the same run, each the median of RUNS (default 3). Then the same drawing 10 x larger (BIG,
# default 10 N) read by camgen alone (ezdxf would take minutes), to show that camgen's memory
# does not grow with the entities beyond the file's own size.
# Targets (issue 28): camgen at least 10 x faster than ezdxf.readfile (CPU time, the wall time
# of a loaded machine being the CPU time stretched; aimed at 15 x for the noise of a shared
# machine), and camgen's peak memory the file plus a constant: peak - file at most
# MEM_CONST_KB (default 16384 KiB: the process itself, about 7 MiB, and the reader's window
# of the file) at both sizes.
# Usage: bench/dxf.sh [N] [BIG]   (BIG=0: the small drawing only)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
camgen=${CAMGEN:-$root/build/camgen}
n=${1:-100000}
big=${2:-$((10 * n))}
runs=${RUNS:-3}
speed_target=10
mem_const_kb=${MEM_CONST_KB:-16384}
py=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }
fails=0
# camgen_read COUNT FILE: dxf-info RUNS times; sets camgen_s (median wall), camgen_cpu (median
# user + system), camgen_kb (the highest peak); checks that it read the circles and the polyline.
camgen_read() {
  local count=$1 file=$2 ct=() ck=() cc=() s e k u sy
  for _ in $(seq "$runs"); do
    s=$(date +%s.%N)
    /usr/bin/time -f "%M %U %S" -o "$work/kb" "$camgen" dxf-info "$file" >"$work/info.txt"
    e=$(date +%s.%N)
    read -r k u sy <"$work/kb"
    ct+=("$(echo "$e - $s" | bc)"); ck+=("$k"); cc+=("$(echo "$u + $sy" | bc)")
  done
  grep -q "diameter 1: $((count / 2)) circles" "$work/info.txt" || { echo "camgen dxf-info did not read the circles"; cat "$work/info.txt"; exit 1; }
  grep -q "^  layer OUTLINE: $count segments" "$work/info.txt" || { echo "camgen dxf-info did not chain the polyline"; cat "$work/info.txt"; exit 1; }
  camgen_s=$(printf '%s\n' "${ct[@]}" | median)
  camgen_kb=$(printf '%s\n' "${ck[@]}" | sort -g | tail -1)
  camgen_cpu=$(printf '%s\n' "${cc[@]}" | median)
}
# memory_target LABEL FILE_BYTES: the PASS/FAIL line of the memory target.
memory_target() {
  local over=$(( camgen_kb - $2 / 1024 ))
  local verdict=PASS
  [ "$over" -le "$mem_const_kb" ] || { verdict=FAIL; fails=$((fails + 1)); }
  echo "$verdict memory ($1): peak - file = $camgen_kb - $(($2 / 1024)) = $over KiB, target at most $mem_const_kb KiB"
}

"$py" "$root/bench/gen_dxf.py" "$work/big.dxf" "$n"
bytes=$(stat -c %s "$work/big.dxf")
echo "drawing: $n circles and a $n-segment polyline, $((bytes / 1024)) KiB"
camgen_read "$n" "$work/big.dxf"
et=(); ew=(); ek=(); ec=()
for _ in $(seq "$runs"); do
  s=$(date +%s.%N)
  /usr/bin/time -f %M -o "$work/kb" "$py" -c "
import sys, time, ezdxf
t = time.perf_counter(); c = time.process_time(); doc = ezdxf.readfile(sys.argv[1])
t = time.perf_counter() - t; c = time.process_time() - c
assert len(doc.modelspace().query('CIRCLE')) == $n
print(t, c)" "$work/big.dxf" >"$work/ez.txt"
  e=$(date +%s.%N)
  read -r w c <"$work/ez.txt"
  et+=("$w"); ec+=("$c"); ew+=("$(echo "$e - $s" | bc)"); ek+=("$(cat "$work/kb")")
done
ez_s=$(printf '%s\n' "${et[@]}" | median)
ez_whole=$(printf '%s\n' "${ew[@]}" | median)
ez_kb=$(printf '%s\n' "${ek[@]}" | sort -g | tail -1)
ez_cpu=$(printf '%s\n' "${ec[@]}" | median)
printf 'camgen dxf-info:   %8.3f s wall, %.3f s CPU, peak %7d KiB (the file: %d KiB)\n' "$camgen_s" "$camgen_cpu" "$camgen_kb" "$((bytes / 1024))"
printf 'ezdxf.readfile:    %8.3f s wall, %.3f s CPU (the python process: %.3f s wall, peak %d KiB)\n' "$ez_s" "$ez_cpu" "$ez_whole" "$ez_kb"
echo "load average while measuring: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores (wall times of a loaded machine are the CPU times stretched)"
ratio_cpu=$(echo "scale=1; $ez_cpu / $camgen_cpu" | bc)
ratio_wall=$(echo "scale=1; $ez_s / $camgen_s" | bc)
verdict=PASS
[ "$(echo "$ratio_cpu >= $speed_target" | bc)" = 1 ] || { verdict=FAIL; fails=$((fails + 1)); }
echo "$verdict speed: camgen reads $ratio_cpu x faster than ezdxf.readfile in CPU time ($ratio_wall x in wall time), target at least $speed_target x"
memory_target "$n circles" "$bytes"

if [ "$big" -gt 0 ]; then
  "$py" "$root/bench/gen_dxf.py" "$work/big.dxf" "$big"
  bytes_big=$(stat -c %s "$work/big.dxf")
  echo "drawing: $big circles and a $big-segment polyline, $((bytes_big / 1024)) KiB (camgen alone)"
  camgen_read "$big" "$work/big.dxf"
  printf 'camgen dxf-info:   %8.3f s wall, %.3f s CPU, peak %7d KiB (the file: %d KiB)\n' "$camgen_s" "$camgen_cpu" "$camgen_kb" "$((bytes_big / 1024))"
  memory_target "$big circles" "$bytes_big"
fi
[ "$fails" -eq 0 ] && echo "all DXF targets met" || echo "$fails DXF target(s) not met"
