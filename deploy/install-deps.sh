#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs exactly the Debian 12 packages that sadr needs, and nothing else.
#   install-deps.sh            what building, testing and running need (CI, Quick start (2))
#   install-deps.sh --product  what building and running the product needs, with the Python
#                              package's plots (Quick start (1)); no test, docs or lint tools
# Idempotent: packages already present are skipped, and apt is not touched at all
# when nothing is missing. Run as root (or with sudo available).
set -euo pipefail

PRODUCT=(
  build-essential cmake pkg-config          # toolchain (g++ 12, CMake 3.25)
  libzmq3-dev cppzmq-dev                    # transport between the three processes
  libprotobuf-dev protobuf-compiler         # wire messages (proto/, sadr.*.v1; framing protocol v2)
  libeigen3-dev                             # small dense/sparse linear algebra
  libboost-graph-dev                        # graph diagnostics (connected_components), Boost.Math
  libgmsh-dev                               # geometry/: reads .msh v2/v4 with physical groups, and STL (docs/geometry.md)
  libassimp-dev                             # geometry/: reads .obj surfaces
  libcli11-dev                              # command-line parsing
  libyaml-cpp-dev                           # scene files
  libmuparser-dev                           # expression rate laws (common/rate_law.hpp)
  nlohmann-json3-dev                        # JSON manifests and benchmark output
  python3 python3-numpy python3-pandas python3-matplotlib python3-yaml  # the Python package's reading and plots
  python3-scipy                             # its confidence bands (Student t), and the validation references
)
TESTS=(
  libgtest-dev libgmock-dev                 # tests
  libbenchmark-dev                          # benchmarks (optional: without it they are not built)
  procps                                    # pgrep, used by the e2e tests to find service processes
  python3-xarray                            # the Python package's xarray views (python/sadr)
  python3-pytest                            # its tests (tests/python, run by ctest)
  flake8                                    # the Python linter of the python_lint test (python/.flake8)
  python3-venv python3-pip                  # python_package: pip install ./python into a venv, offline
  python3-distributed                       # the Dask example (python/sadr/dask_runner.py)
  python3-nbconvert python3-ipykernel       # the notebook examples/notebooks/, executed in the tests
  clang-format                              # .ci/run fails on a formatting difference
  mkdocs                                    # the docs site (mkdocs.yml), built --strict by the tests (tests/docs)
)

case "${1:-}" in
  "") PACKAGES=("${PRODUCT[@]}" "${TESTS[@]}") ;;
  --product) PACKAGES=("${PRODUCT[@]}") ;;
  *) echo "install-deps: unknown option '$1'; allowed: --product, or nothing" >&2; exit 2 ;;
esac

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get -o DPkg::Lock::Timeout=900 install -y -q --no-install-recommends "${missing[@]}"
