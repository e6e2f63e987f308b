#!/usr/bin/env bash
# Fresh Debian machine -> the main job: installs what is missing, builds contactrb in
# Release (build/, or $CONTACTRB_BUILD_DIR), and runs it on the default case. Outputs go
# to out/demo/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# shellcheck source-path=SCRIPTDIR/..
source scripts/install-deps.sh

build_dir=${CONTACTRB_BUILD_DIR:-build}
contactrb_install_deps
# Same build/ configuration as scripts/test.sh; the executables and, when pybind11 and the
# Python headers are there, the Python module (PYTHONPATH=build/python: docs/python.md).
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
targets=(contactrb)
if cmake --build "$build_dir" --target help | grep -q '^\.\.\. contactrb_python$'; then targets+=(contactrb_python); fi
cmake --build "$build_dir" -j "$(contactrb_jobs)" --target "${targets[@]}"

"$build_dir/apps/contactrb/contactrb" --version
# The main job: hertz-b end to end (training snapshots, offline with CPG, evaluation of the
# reduced model against the HF solver on the verification set), then one reduced solve with
# its fields reconstructed on the HF mesh for ParaView.
"$build_dir/apps/contactrb/contactrb" demo --out out/demo
mkdir -p out/demo/online
"$build_dir/apps/contactrb/contactrb" online --model out/demo/model.h5 --mu 1.05 --out out/demo/online > out/demo/online/solution.json
echo "contactrb: demo outputs in out/demo/ (evaluation.csv; open out/demo/online/solution.vtu in ParaView)"
