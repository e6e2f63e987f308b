#!/usr/bin/env bash
# The 3D HF scaling sweep of docs/performance.md ("HF scaling in 3D"): hertz-3d at mu = 0.02
# (collocation), the built-in levels, Newton (default tolerance 1e-10) and Kacanov (the paper's
# alpha = 0.3, eps_KA = 1e-3), one process per configuration (peak RSS per configuration), the
# Newton with the AMG Krylov solve of its systems (--linear-solver amg, docs/solvers.md), then
# CHOLMOD's symbolic count of the factor of A_00 on the level above (bench_a00_factorization
# --analysis-only: where the direct factorization stops fitting).
# First the default path of `contactrb solve --solver newton` (--linear-solver auto, --sequence -1:
# the direct solve below 40 000 free DOFs, the AMG one with one coarse stage from level 3 on),
# with a mesh of about 1e5 DOFs between levels 2 and 3 (--fine-size 0.006, cold: no level of its own).
#   bench/hf_scaling_3d.sh BUILD_DIR [MAX_NEWTON_LEVEL] [MAX_KACANOV_LEVEL] [MAX_AMG_LEVEL] [MAX_DEFAULT_LEVEL] > scaling_3d.csv
# (MAX_AMG_LEVEL or MAX_DEFAULT_LEVEL 4: 1.2e6 DOFs, about 80 s of mesh generation, 4.5 GB.)
set -uo pipefail
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}  # as bench/hf_scaling.sh
build=${1:-build}
max_newton=${2:-3}
max_kacanov=${3:-2}
max_amg=${4:-3}
max_default=${5:-3}
bin="$build/bench/bench_hf_scaling"
"$bin" --header
default=$(for level in $(seq 0 "$max_default"); do
  "$bin" --case hertz-3d --level "$level" --mu 0.02 --solver newton --linear-solver auto --sequence -1 --threads 1 \
    --repeat $((level < 3 ? 3 : 1))
done)
echo "$default"
echo "$default" | awk -F, 'NR > 1 { printf "default level %d -> %d: N^%.2f\n", level, $2, log($10 / t) / log($3 / n) >"/dev/stderr" }
                           { level = $2; n = $3; t = $10 }'
"$bin" --case hertz-3d --level 3 --fine-size 0.006 --mu 0.02 --solver newton --linear-solver auto --threads 1
newton=$(for level in $(seq 0 "$max_newton"); do
  "$bin" --case hertz-3d --level "$level" --mu 0.02 --solver newton --repeat $((level < 3 ? 3 : 1))
done)
echo "$newton"
# The growth exponent of the wall time (total_s) between consecutive levels, on stderr.
echo "$newton" | awk -F, 'NR > 1 { printf "newton level %d -> %d: N^%.2f\n", level, $2, log($10 / t) / log($3 / n) >"/dev/stderr" }
                          { level = $2; n = $3; t = $10 }'
amg=$(for level in $(seq 0 "$max_amg"); do
  "$bin" --case hertz-3d --level "$level" --mu 0.02 --solver newton --linear-solver amg --threads 1 \
    --repeat $((level < 3 ? 3 : 1))
done)
echo "$amg"
echo "$amg" | awk -F, 'NR > 1 { printf "newton amg level %d -> %d: N^%.2f\n", level, $2, log($10 / t) / log($3 / n) >"/dev/stderr" }
                       { level = $2; n = $3; t = $10 }'
for level in $(seq 0 "$max_kacanov"); do
  "$bin" --case hertz-3d --level "$level" --mu 0.02 --solver kacanov --repeat $((level < 2 ? 3 : 1))
done
"$build/bench/bench_a00_factorization" $((max_newton + 1)) 1 cholmod node-metis --case hertz-3d --analysis-only >&2
