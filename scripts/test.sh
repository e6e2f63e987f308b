#!/usr/bin/env bash
# Installs what is missing, builds contactrb with its tests and runs the whole suite.
#   ./scripts/test.sh              Release build in build/
#   ./scripts/test.sh --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
#                                  (with a longer fuzz run: docs/testing.md)
# CONTACTRB_BUILD_DIR=DIR overrides the build directory.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# shellcheck source-path=SCRIPTDIR/..
source scripts/install-deps.sh

build_dir=${CONTACTRB_BUILD_DIR:-build}
config=(-DCMAKE_BUILD_TYPE=Release)
sanitize=0
for arg in "$@"; do
  case "$arg" in
    --sanitize)
      build_dir=${CONTACTRB_BUILD_DIR:-build-asan}
      config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCONTACTRB_SANITIZE=ON)
      sanitize=1
      ;;
    -h|--help)
      sed -n '2,6p' "$0"
      exit 0
      ;;
    *)
      echo "test.sh: unknown argument '$arg' (usage: ./scripts/test.sh [--sanitize])" >&2
      exit 2
      ;;
  esac
done

contactrb_install_deps
cmake -S . -B "$build_dir" "${config[@]}" -DCONTACTRB_BUILD_TESTS=ON
cmake --build "$build_dir" -j "$(contactrb_jobs)"
# Sanitizer reports fail the test; leaks are reported too.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
if [[ "$sanitize" == 1 ]]; then
  # The longer fuzz run under the sanitizers (docs/testing.md); an explicit value is kept.
  export CONTACTRB_FUZZ_CASES="${CONTACTRB_FUZZ_CASES:-400}"
  export CONTACTRB_FUZZ_SECONDS="${CONTACTRB_FUZZ_SECONDS:-180}"
fi
ctest --test-dir "$build_dir" --output-on-failure -j2
