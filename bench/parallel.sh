#!/usr/bin/env bash
# The parallel speed-ups of docs/parallel.md ("Measured speed-ups"): wall clock of
#  1. `snapshots` over a set on 1 and 2 MPI ranks (and 1 and 2 threads, --jobs), at mesh level
#     LEVEL: the wall clock of the solves as the command reports it ("solves X s": without the
#     process start, mpirun's and the reference mesh) and of the whole command,
#  2. `online --batch` on 1 and 2 threads (--jobs) over LINES random lines, in each --format,
#  3. `sample --n LINES` on 1 and 2 threads, and `sample --n N` (all hardware threads).
# Each comparison runs its 1-worker (A) and 2-worker (B) commands interleaved, REPEAT rounds in
# the order A B, B A, A B, ... so that a drift of the machine's speed (minutes to hours on a
# shared host) lands on both sides instead of in the ratio. Every sample is printed; the
# summary gives the fastest and the median of each side, their ratios, and the median of the
# rounds' ratios A_i / B_i (each from two runs a few seconds apart: the drift-free figure).
# MPIRUN_FLAGS (environment): extra options for mpirun.
# SNAPSHOT_FLAGS (environment): extra options for `snapshots` (e.g. "--tol 1e-4"); a larger LEVEL
# shows the speed-up where the fixed costs (process start, MPI_Init, mesh, file) matter less.
# ONLY (environment): a regular expression; only the comparisons whose label matches are run
# (e.g. ONLY='online|sample'; the labels: snapshots-threads, ceiling-snapshots, snapshots-mpi,
# ceiling-online, online-json, online-csv, online-npy, sample, sample-n).
# The "ceiling" comparisons run the same work as two independent 1-worker processes at once (the
# two halves of the set or batch): what 2 workers can give on this machine at this moment with
# nothing shared (memory bandwidth, caches, frequency and other load included); a 2-thread or
# 2-rank speed-up is to be read against it.
# CASE must have one parameter (the batch file is the first column of `sample --points`).
#   bench/parallel.sh BUILD_DIR [CASE] [SET] [LEVEL] [LINES] [N] [REPEAT]
#   e.g. bench/parallel.sh build hertz-b training 3 200000 1000000 5
set -euo pipefail
build=${1:-build}
case=${2:-hertz-b}
set_name=${3:-training}
level=${4:-1}
lines=${5:-200000}
n=${6:-1000000}
repeat=${7:-3}
only=${ONLY:-.}
cli=$(realpath "$build/apps/contactrb/contactrb")
mpirun=$(command -v mpirun || true)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# CPU time (s) used on the whole machine so far (/proc/stat: user, nice, system, irq, softirq,
# steal) and by this shell's finished children (`own_cpu` sets `own`: bash `times` run in this
# shell, as a subshell, $(...) or a pipeline, has no children of its own).
clk=$(getconf CLK_TCK)
machine_cpu() { awk -v c="$clk" '/^cpu / {printf "%.3f", ($2 + $3 + $4 + $7 + $8 + $9) / c}' /proc/stat; }
own_cpu() { times >"$work/times"; own=$(tail -n 1 "$work/times" | awk '{n = 0; for (i = 1; i <= 2; ++i) {split($i, p, "m"); n += 60 * p[1] + substr(p[2], 1, length(p[2]) - 1)} printf "%.3f", n}'); }
# One run of the command: its wall clock (s) in run_wall, the "solves X s" of its summary (if
# any; the longest when it ran several processes) in run_solves, and in run_other the cores
# used meanwhile by other processes (the machine's CPU time less the command's, over the wall
# clock): a run that shared the machine shows it, whatever the load average says.
run_once() {
  local s e out m0 m1 o0 o1
  m0=$(machine_cpu); own_cpu; o0=$own
  s=$(date +%s.%N)
  out=$("$@" 2>/dev/null)
  e=$(date +%s.%N)
  m1=$(machine_cpu); own_cpu; o1=$own
  run_wall=$(echo "$e - $s" | bc -l)
  run_solves=$(echo "$out" | sed -n 's/.*solves \([0-9.]*\) s.*/\1/p' | sort -g | tail -n 1)
  run_other=$(echo "o = ($m1 - $m0 - ($o1 - $o0)) / $run_wall; if (o < 0) o = 0; o" | bc -l)
}
# Statistics of whitespace-separated samples: "fastest median".
stats() { tr ' ' '\n' <<<"$1" | grep . | sort -g | awk '{v[NR]=$1} END {m = NR % 2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2; printf "%.3f %.3f", v[1], m}'; }
# Median of the ratios a_i / b_i of two sample lists (of the rounds whose flag in the optional
# third list is 1; "-" when none).
ratio_median() {
  paste <(tr ' ' '\n' <<<"$1" | grep .) <(tr ' ' '\n' <<<"$2" | grep .) <(tr ' ' '\n' <<<"${3:-}" | grep . || yes 1 | head -n 1000) |
    awk 'NF >= 2 && ($3 == "" || $3 == 1) {print $1/$2}' | sort -g |
    awk '{v[NR]=$1} END {if (NR == 0) {printf "-"; exit} m = NR % 2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2; printf "%.2f", m}'
}
ratio() { printf '%.2f' "$(echo "$1 / $2" | bc -l)"; }
# Two lines per measure: the samples, then the fastest, the medians and the speed-ups.
summary() {  # label, samples of A, samples of B, quiet flags of the rounds
  local a_best a_med b_best b_med
  read -r a_best a_med <<<"$(stats "$2")"
  read -r b_best b_med <<<"$(stats "$3")"
  echo "  $1: 1 [$2] -> 2 [$3] s"
  echo "    fastest ${a_best} -> ${b_best} s ($(ratio "$a_best" "$b_best")x), median ${a_med} -> ${b_med} s ($(ratio "$a_med" "$b_med")x), median of the rounds' ratios $(ratio_median "$2" "$3")x, of the quiet rounds' $(ratio_median "$2" "$3" "$4")x"
}
# A round is quiet when other processes used less than QUIET cores (default 0.1) during each of
# its two runs.
quiet=${QUIET:-0.1}
# compare LABEL DESCRIPTION FUNCTION_A FUNCTION_B: the interleaved rounds (the functions run the
# commands); summaries of the whole command and, when the commands report them, of the solves.
compare() {
  [[ "$1" =~ $only ]] || return 0
  local wa="" wb="" sa="" sb="" oa="" ob="" q="" i qa qb
  for i in $(seq "$repeat"); do
    if (( i % 2 )); then
      run_once "$3"; wa+="$run_wall "; sa+="$run_solves "; qa=$run_other
      run_once "$4"; wb+="$run_wall "; sb+="$run_solves "; qb=$run_other
    else
      run_once "$4"; wb+="$run_wall "; sb+="$run_solves "; qb=$run_other
      run_once "$3"; wa+="$run_wall "; sa+="$run_solves "; qa=$run_other
    fi
    oa+="$(printf '%.2f' "$qa") "; ob+="$(printf '%.2f' "$qb") "
    q+="$(echo "$qa < $quiet && $qb < $quiet" | bc -l) "
  done
  echo "$2 (load average now $(cut -d' ' -f1-3 /proc/loadavg)):"
  echo "  cores used by other processes during the runs: 1 [$oa] 2 [$ob]; quiet rounds (< $quiet): $(tr ' ' '\n' <<<"$q" | grep -c 1) of $repeat"
  [[ -n "${sa// /}" ]] && summary "solves" "$sa" "$sb" "$q"
  wa=$(printf '%.3f ' $wa); wb=$(printf '%.3f ' $wb)
  summary "whole command" "$wa" "$wb" "$q"
}

echo "machine: $(nproc) hardware threads; load average before: $(cut -d' ' -f1-3 /proc/loadavg); $repeat rounds"
cd "$work"
"$cli" offline --case "$case" -q --out model.h5 >/dev/null
read -r -a snapshot_flags <<<"${SNAPSHOT_FLAGS:-}"
read -r -a mpirun_flags <<<"${MPIRUN_FLAGS:-}"
snapshots=(snapshots --case "$case" --set "$set_name" --level "$level" "${snapshot_flags[@]}" -q --out s.h5)
snap_j1() { "$cli" "${snapshots[@]}"; }
snap_j2() { "$cli" "${snapshots[@]}" --jobs 2; }
compare snapshots-threads "snapshots $case $set_name level $level${SNAPSHOT_FLAGS:+ $SNAPSHOT_FLAGS}, 1 -> 2 threads" snap_j1 snap_j2
# The machine's own ceiling for the same work on its 2 cores: the two halves of the set as two
# independent processes at once (`--part 1/2` and `--part 2/2`, as two array jobs), nothing shared.
snap_halves() { "$cli" "${snapshots[@]/s.h5/s1.h5}" --part 1/2 & "$cli" "${snapshots[@]/s.h5/s2.h5}" --part 2/2; wait; }
compare ceiling-snapshots "ceiling: snapshots $case $set_name level $level${SNAPSHOT_FLAGS:+ $SNAPSHOT_FLAGS}, 1 process -> its two halves (--part) as 2 processes at once" snap_j1 snap_halves
if [[ -n "$mpirun" ]]; then
  # MPIRUN_FLAGS: extra mpirun options, e.g. "--mca pml ob1" (MPI_Init without probing for
  # Omni-Path/libfabric networks: 0.03 s instead of 0.23 s on the development machine).
  snap_np1() { "$mpirun" --oversubscribe "${mpirun_flags[@]}" -np 1 "$cli" "${snapshots[@]}"; }
  snap_np2() { "$mpirun" --oversubscribe "${mpirun_flags[@]}" -np 2 "$cli" "${snapshots[@]}"; }
  compare snapshots-mpi "snapshots $case $set_name level $level${SNAPSHOT_FLAGS:+ $SNAPSHOT_FLAGS}, 1 -> 2 MPI ranks${MPIRUN_FLAGS:+ ($MPIRUN_FLAGS)}" snap_np1 snap_np2
fi
"$cli" sample --model model.h5 --n "$lines" --seed 1 --jobs 1 --no-plot --out p.csv --points points.csv >/dev/null
cut -d, -f2 points.csv | tail -n +2 > batch.txt
# The ceiling for `online`: the two halves of the batch as two 1-thread processes at once.
half=$(( (lines + 1) / 2 ))
head -n "$half" batch.txt > batch1.txt
tail -n +"$((half + 1))" batch.txt > batch2.txt
online_halves() {
  "$cli" online --model model.h5 --batch batch1.txt --format csv --jobs 1 >/dev/null &
  "$cli" online --model model.h5 --batch batch2.txt --format csv --jobs 1 >/dev/null
  wait
}
online_csv_whole() { "$cli" online --model model.h5 --batch batch.txt --format csv --jobs 1 >/dev/null; }
compare ceiling-online "ceiling: online --batch $case --format csv, $lines lines, 1 process -> its two halves as 2 processes at once" online_csv_whole online_halves
for format in json csv npy; do
  eval "online_${format}_1() { \"\$cli\" online --model model.h5 --batch batch.txt --format $format --jobs 1 >/dev/null; }"
  eval "online_${format}_2() { \"\$cli\" online --model model.h5 --batch batch.txt --format $format --jobs 2 >/dev/null; }"
  compare "online-$format" "online --batch $case --format $format, $lines lines, 1 -> 2 threads" "online_${format}_1" "online_${format}_2"
done
sample_1() { "$cli" sample --model model.h5 --n "$lines" --jobs 1 --no-plot --out q.csv >/dev/null; }
sample_2() { "$cli" sample --model model.h5 --n "$lines" --jobs 2 --no-plot --out q.csv >/dev/null; }
compare sample "sample $case --n $lines --no-plot, 1 -> 2 threads" sample_1 sample_2
if [[ sample-n =~ $only ]]; then
  t=""
  for _ in $(seq "$repeat"); do run_once "$cli" sample --model model.h5 --n "$n" --out q.csv; t+="$run_wall "; done
  read -r t_best t_med <<<"$(stats "$t")"
  echo "sample $case, n = $n, all threads, with the figure: [$(printf '%.3f ' $t)] s, fastest ${t_best} s, median ${t_med} s"
fi
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
