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
# Same build/ configuration as scripts/test.sh; only the executable is built here.
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build_dir" -j "$(contactrb_jobs)" --target contactrb

"$build_dir/apps/contactrb/contactrb" --version
"$build_dir/apps/contactrb/contactrb" cases
"$build_dir/apps/contactrb/contactrb" mesh --case hertz-b --out out/demo
# One high-fidelity contact solve of the default case (a later issue replaces this job
# with `contactrb demo`: snapshots, offline, online).
"$build_dir/apps/contactrb/contactrb" solve --case hertz-b --mu 1.05 --out out/demo
echo "contactrb: demo outputs in out/demo/ (open out/demo/solution.vtu in ParaView)"
