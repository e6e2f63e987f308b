#!/usr/bin/env bash
# The parallel speed-ups of docs/cluster.md ("Measured speed-ups"): wall clock of
#  1. `snapshots` over a set on 1 and 2 MPI ranks (and 1 and 2 threads, --jobs), at mesh level
#     LEVEL: the wall clock of the solves as the command reports it ("solves X s": without the
#     process start, mpirun's and the reference mesh) and of the whole command,
#  2. `online --batch` on 1 and 2 threads (--jobs) over LINES random lines, in each --format,
#  3. `sample --n N` (all hardware threads).
# Each run is repeated REPEAT times and the fastest kept (the machine may be shared).
# MPIRUN_FLAGS (environment): extra options for mpirun.
# SNAPSHOT_FLAGS (environment): extra options for `snapshots` (e.g. "--tol 1e-4"); a larger LEVEL
# shows the speed-up where the fixed costs (process start, MPI_Init, mesh, file) matter less.
# CASE must have one parameter (the batch file is the first column of `sample --points`).
#   bench/parallel.sh BUILD_DIR [CASE] [SET] [LEVEL] [LINES] [N] [REPEAT]
#   e.g. bench/parallel.sh build hertz-b training 1 200000 1000000 3
set -euo pipefail
build=${1:-build}
case=${2:-hertz-b}
set_name=${3:-training}
level=${4:-1}
lines=${5:-200000}
n=${6:-1000000}
repeat=${7:-3}
cli=$(realpath "$build/apps/contactrb/contactrb")
mpirun=$(command -v mpirun || true)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# Fastest wall clock (s) of `repeat` runs of the command.
best() {
  local b="" t
  for _ in $(seq "$repeat"); do
    local s e
    s=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    e=$(date +%s.%N)
    t=$(echo "$e - $s" | bc -l)
    if [[ -z "$b" ]] || (( $(echo "$t < $b" | bc -l) )); then b=$t; fi
  done
  printf '%.3f' "$b"
}
ratio() { printf '%.2f' "$(echo "$1 / $2" | bc -l)"; }

echo "machine: $(nproc) hardware threads; load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
cd "$work"
"$cli" offline --case "$case" -q --out model.h5 >/dev/null
# Fastest "solves" wall clock (s) and fastest total (s) of `repeat` runs of a snapshots command.
snap() {
  local bs="" bt=""
  for _ in $(seq "$repeat"); do
    local s e out t solves
    s=$(date +%s.%N)
    out=$("$@" 2>/dev/null)
    e=$(date +%s.%N)
    t=$(echo "$e - $s" | bc -l)
    solves=$(echo "$out" | sed -n 's/.*solves \([0-9.]*\) s.*/\1/p')
    if [[ -z "$bs" ]] || (( $(echo "$solves < $bs" | bc -l) )); then bs=$solves; fi
    if [[ -z "$bt" ]] || (( $(echo "$t < $bt" | bc -l) )); then bt=$t; fi
  done
  printf '%s %.3f' "$bs" "$bt"
}
report() {  # label, then "solves total" of 1 and of 2
  read -r s1 w1 <<<"$2"
  read -r s2 w2 <<<"$3"
  echo "$1: solves ${s1} s -> ${s2} s (speed-up $(ratio "$s1" "$s2")); whole command ${w1} s -> ${w2} s (speed-up $(ratio "$w1" "$w2"))"
}
read -r -a snapshot_flags <<<"${SNAPSHOT_FLAGS:-}"
snapshots=(snapshots --case "$case" --set "$set_name" --level "$level" "${snapshot_flags[@]}" -q --out s.h5)
report "snapshots $case $set_name level $level${SNAPSHOT_FLAGS:+ $SNAPSHOT_FLAGS}, 1 -> 2 threads" "$(snap "$cli" "${snapshots[@]}")" \
  "$(snap "$cli" "${snapshots[@]}" --jobs 2)"
if [[ -n "$mpirun" ]]; then
  # MPIRUN_FLAGS: extra mpirun options, e.g. "--mca pml ob1" (MPI_Init without probing for
  # Omni-Path/libfabric networks: 0.03 s instead of 0.23 s on the development machine).
  read -r -a mpirun_flags <<<"${MPIRUN_FLAGS:-}"
  report "snapshots $case $set_name level $level${SNAPSHOT_FLAGS:+ $SNAPSHOT_FLAGS}, 1 -> 2 MPI ranks${MPIRUN_FLAGS:+ ($MPIRUN_FLAGS)}" \
    "$(snap "$mpirun" --oversubscribe "${mpirun_flags[@]}" -np 1 "$cli" "${snapshots[@]}")" \
    "$(snap "$mpirun" --oversubscribe "${mpirun_flags[@]}" -np 2 "$cli" "${snapshots[@]}")"
fi
"$cli" sample --model model.h5 --n "$lines" --seed 1 --jobs 1 --no-plot --out p.csv --points points.csv >/dev/null
cut -d, -f2 points.csv | tail -n +2 > batch.txt
for format in json csv npy; do
  b1=$(best "$cli" online --model model.h5 --batch batch.txt --format "$format" --jobs 1)
  b2=$(best "$cli" online --model model.h5 --batch batch.txt --format "$format" --jobs 2)
  echo "online --batch $case --format $format, $lines lines: 1 thread ${b1} s ($(printf '%.0f' "$(echo "$lines / $b1" | bc -l)")/s), 2 threads ${b2} s ($(printf '%.0f' "$(echo "$lines / $b2" | bc -l)")/s): speed-up $(ratio "$b1" "$b2")"
done
s1=$(best "$cli" sample --model model.h5 --n "$lines" --jobs 1 --no-plot --out q.csv)
s2=$(best "$cli" sample --model model.h5 --n "$lines" --jobs 2 --no-plot --out q.csv)
echo "sample $case, n = $lines: 1 thread ${s1} s, 2 threads ${s2} s: speed-up $(ratio "$s1" "$s2")"
sn=$(best "$cli" sample --model model.h5 --n "$n" --out q.csv)
echo "sample $case, n = $n, all threads, with the figure: ${sn} s"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
