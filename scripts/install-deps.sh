#!/usr/bin/env bash
# Installs the Debian packages contactrb needs, only those missing (idempotent).
# Sourced by demo.sh and test.sh; can also be run on its own.
set -euo pipefail

CONTACTRB_DEBIAN_PACKAGES=(
  build-essential cmake g++ pkg-config
  libeigen3-dev libcli11-dev libgmsh-dev libhdf5-dev libtomlplusplus-dev libsuitesparse-dev
  libopenblas0-pthread liblapack-dev  # LAPACK/BLAS (OpenBLAS at run time): the dense Newton systems (solve/dense_lu.hpp)
  nlohmann-json3-dev
  libhypre-dev  # BoomerAMG: the AMG Krylov solver of the Newton systems (docs/solvers.md)
  libopenmpi-dev openmpi-bin  # optional at build time: mpirun runs (docs/parallel.md)
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-meshio python3-numpy python3-matplotlib
  python3-h5py  # the file-format test: an independent reader of model files (tests/io/test_model_h5py.py)
  python3-dev pybind11-dev python3-pytest  # the Python module (python/, docs/python.md) and its tests
  python3-paraview xvfb  # the ParaView test: pvpython renders a VTU under xvfb-run (tests/io/paraview_check.py)
)

contactrb_install_deps() {
  local missing=()
  local pkg
  for pkg in "${CONTACTRB_DEBIAN_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done
  if [ "${#missing[@]}" -eq 0 ]; then
    echo "contactrb: all ${#CONTACTRB_DEBIAN_PACKAGES[@]} Debian packages are installed"
    return 0
  fi
  echo "contactrb: installing missing Debian packages: ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    if ! command -v sudo >/dev/null 2>&1; then
      echo "contactrb: need root or sudo to install: ${missing[*]}" >&2
      return 1
    fi
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
}

# Number of parallel build jobs: all cores, at most 8 (keeps memory in check).
contactrb_jobs() {
  local n
  n=$(nproc 2>/dev/null || echo 2)
  if [ "$n" -gt 8 ]; then n=8; fi
  echo "$n"
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
  contactrb_install_deps
fi
