#!/usr/bin/env bash
# The HF scaling sweep of docs/performance.md ("HF solve by level"): hertz-a at mu = 0.3, whole-mesh
# refinement levels, both solvers (Kacanov with the paper's alpha = 0.3, eps_KA = 1e-3; Newton with
# its default tolerance 1e-10), one process per configuration (peak RSS per configuration).
#   bench/hf_scaling.sh BUILD_DIR [MAX_NEWTON_LEVEL] [MAX_KACANOV_LEVEL] > scaling.csv
set -uo pipefail
# One BLAS thread: the dense reduced systems are small, and the CPU-time column then measures
# the work (the development machine is shared; OpenBLAS threads spin while waiting). Newton's
# factorization of A_00 and its selected-inverse blocks (BLAS 3) still use the hardware threads
# from 200 000 free DOFs on: bench_hf_scaling's --threads default (docs/performance.md, "BLAS
# threads"; pass --threads 1 through THREADS=1 for a single-thread sweep).
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
threads=()
[ -n "${THREADS:-}" ] && threads=(--threads "$THREADS")
build=${1:-build}
max_newton=${2:-6}
max_kacanov=${3:-5}
bin="$build/bench/bench_hf_scaling"
"$bin" --header
for level in $(seq 0 "$max_newton"); do
  "$bin" --case hertz-a --level "$level" --mu 0.3 --solver newton --repeat $((level < 4 ? 3 : 1)) "${threads[@]}"
done
for level in $(seq 0 "$max_kacanov"); do
  "$bin" --case hertz-a --level "$level" --mu 0.3 --solver kacanov --repeat $((level < 4 ? 3 : 1))
done
