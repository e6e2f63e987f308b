#!/usr/bin/env bash
# Warm starts and grid sequencing in snapshot sweeps (docs/performance.md, "Warm starts and grid
# sequencing in snapshot sweeps"): `contactrb snapshots --solver newton` over a case's training set,
# one thread, in four starts: cold (--warm-start off --sequence 0), every solve sequenced
# (--warm-start off --sequence K), warm from the nearest solved point (--warm-start on --sequence 0)
# and the default (--warm-start on --sequence -1: warm, the first wave sequenced where the automatic
# rule sequences). One CSV line per case and start: Newton iterations (mean, median, max) and wall
# time per solve, for the first solve (the only cold one of a warm sweep) and the others apart; the
# mean thread CPU time per solve (the figure to compare on a busy machine).
#   bench/snapshot_warm_start.sh BUILD_DIR [CASE:LEVEL[:K] ...] > warm.csv
# K: the coarse levels of the sequenced run (default 2; levels below 0 are skipped, so hertz-3d:1
# has none). Default cases: hertz-a:4 ring-block:2 hertz-3d:1 hertz-3d:2:1.
set -uo pipefail
build=${1:-build}
shift || true
cases=("$@")
[ ${#cases[@]} -eq 0 ] && cases=(hertz-a:4 ring-block:2 hertz-3d:1 hertz-3d:2:1)
bin="$build/apps/contactrb/contactrb"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "case,level,warm_start,sequence,solves,first_iterations,first_s,others_mean_iterations,others_median_iterations,others_max_iterations,others_mean_s,mean_s,mean_cpu_s"
for c in "${cases[@]}"; do
  IFS=: read -r name level k <<<"$c"
  for start in "off 0" "off ${k:-2}" "on 0" "on -1"; do
    set -- $start
    # -j 1: the progress lines come in the schedule's order (the first is the first wave's).
    if ! "$bin" snapshots --case "$name" --level "$level" --solver newton --jobs 1 --warm-start "$1" --sequence "$2" \
      --out "$tmp/s.h5" >"$tmp/summary.txt" 2>"$tmp/progress.txt"; then
      echo "$name,$level,$1,$2,failed" && continue
    fi
    # "snapshot k/n: mu = ... converged in I iterations, T s"
    python3 - "$name" "$level" "$1" "$2" "$tmp/progress.txt" "$tmp/summary.txt" <<'PY'
import re, statistics, sys
name, level, warm, seq, path, summary = sys.argv[1:]
cpu = re.search(r"time per solve: [0-9.]+ s wall, ([0-9.]+) s CPU", open(summary).read()).group(1)
runs = [(int(i), float(t)) for i, t in re.findall(r"converged in (\d+) iterations, ([0-9.]+) s", open(path).read())]
others = runs[1:]
its = [i for i, _ in others]
print(f"{name},{level},{warm},{seq},{len(runs)},{runs[0][0]},{runs[0][1]:.3f},"
      f"{statistics.mean(its) if its else 0:.2f},{statistics.median(its) if its else 0:.1f},{max(its, default=0)},"
      f"{statistics.mean(t for _, t in others) if others else 0:.3f},{statistics.mean(t for _, t in runs):.3f},{cpu}")
PY
  done
done
