#!/usr/bin/env bash
# Cost of the greedy's steps against its HF solves (docs/offline-online.md, "Greedy sampling"):
# `contactrb offline --greedy` on a case and level, with the lazy sweep (--greedy-saturation 1,
# the default) and the full sweep (inf). One CSV line per run from its greedy.csv: steps, HF
# solves, online solves of the sweeps, the sums of the build, sweep and HF times, the last step's
# build and sweep, the greedy's wall time and its ratio to the sum of the HF times.
#   bench/greedy_cost.sh BUILD_DIR [CASE:LEVEL[:MAX_HF] ...] > greedy_cost.csv
# Default: hertz-3p:0 hertz-3p:2:25.
set -uo pipefail
build=${1:-build}
shift || true
cases=("$@")
[ ${#cases[@]} -eq 0 ] && cases=(hertz-3p:0 hertz-3p:2:25)
bin="$build/apps/contactrb/contactrb"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "case,level,saturation,status,steps,hf_solves,sweep_solves,build_s,sweep_s,hf_s,last_build_s,last_sweep_s,greedy_s,greedy_over_hf"
for c in "${cases[@]}"; do
  IFS=: read -r name level max_hf <<<"$c"
  for tau in 1 inf; do
    rm -rf "$tmp/run" && mkdir "$tmp/run"
    if ! "$bin" offline --greedy --case "$name" --level "$level" --max-hf "${max_hf:-50}" --greedy-saturation "$tau" -q \
      --out "$tmp/run/m.h5" >"$tmp/run/summary.txt" 2>&1; then
      echo "$name,$level,$tau,failed" && continue
    fi
    python3 - "$tmp/run" "$name" "$level" "$tau" <<'PY'
import csv, json, sys
run, name, level, tau = sys.argv[1:]
rows = list(csv.DictReader(open(run + "/greedy.csv")))
g = json.load(open(run + "/greedy.json"))
f = lambda k: sum(float(r[k]) for r in rows)
hf = f("hf_s") + g["times_s"]["start_hf"]
total = g["times_s"]["greedy"]
print(f"{name},{level},{tau},{g['status']},{len(rows)},{g['hf_solves']},{int(f('sweep_solves'))},{f('build_s'):.3f},"
      f"{f('sweep_s'):.3f},{hf:.3f},{float(rows[-1]['build_s']):.3f},{float(rows[-1]['sweep_s']):.3f},{total:.3f},{total / hf:.1f}")
PY
  done
done
