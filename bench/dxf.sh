#!/usr/bin/env bash
# bench/run dxf: camgen's DXF reader against ezdxf (issue 28): a drawing of N circles and an
# N-segment polyline (bench/gen_dxf.py, written by ezdxf), read by `camgen dxf-info` (read,
# every circle grouped by diameter, the polyline chained and measured: the whole process) and
# by ezdxf.readfile (the call alone, timed inside python, and the whole python process), in
# the same run, each the median of RUNS (default 3). Target: camgen at least 10 x faster than
# ezdxf.readfile, and camgen's peak memory within the file's size plus a constant.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
camgen=${CAMGEN:-$root/build/camgen}
n=${1:-100000}
runs=${RUNS:-3}
py=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }
"$py" "$root/bench/gen_dxf.py" "$work/big.dxf" "$n"
bytes=$(stat -c %s "$work/big.dxf")
echo "drawing: $n circles and a $n-segment polyline, $((bytes / 1024)) KiB"
ct=() ; ck=() ; cc=()
for _ in $(seq "$runs"); do
  s=$(date +%s.%N)
  /usr/bin/time -f "%M %U %S" -o "$work/kb" "$camgen" dxf-info "$work/big.dxf" >"$work/info.txt"
  e=$(date +%s.%N)
  read -r k u sy <"$work/kb"
  ct+=("$(echo "$e - $s" | bc)"); ck+=("$k"); cc+=("$(echo "$u + $sy" | bc)")
done
grep -q "diameter 1: $((n / 2)) circles" "$work/info.txt" || { echo "camgen dxf-info did not read the circles"; cat "$work/info.txt"; exit 1; }
grep -q "^  layer OUTLINE: $n segments" "$work/info.txt" || { echo "camgen dxf-info did not chain the polyline"; cat "$work/info.txt"; exit 1; }
camgen_s=$(printf '%s\n' "${ct[@]}" | median)
camgen_kb=$(printf '%s\n' "${ck[@]}" | sort -g | tail -1)
camgen_cpu=$(printf '%s\n' "${cc[@]}" | median)
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
echo "target: camgen reads at least 10 x faster than ezdxf.readfile: $(echo "scale=1; $ez_s / $camgen_s" | bc) x in wall time, $(echo "scale=1; $ez_cpu / $camgen_cpu" | bc) x in CPU time"
over=$(( camgen_kb - bytes / 1024 ))
echo "target: memory within the file plus a constant: peak - file = $over KiB"
