#!/usr/bin/env bash
# Installs the Debian packages rodlab needs that are missing (and only those), then
# configures and builds rodlab in Release under build/. Idempotent: a second run installs
# nothing and rebuilds only what changed. Used by `make test`, `make validate`, `make bench`.
# RODLAB_BUILD_TARGETS (space-separated CMake targets) builds only those (`make validate`: the
# command line alone); unset, everything (tests and benchmarks too).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake make g++ pkg-config        # toolchain
  libeigen3-dev                    # linear algebra
  libfmt-dev                       # formatting numbers in error messages
  libsundials-dev                  # KINSOL, IDA (built with KLU)
  libsuitesparse-dev               # KLU sparse LU
  libgsl-dev                       # special functions, quadrature
  libceres-dev                     # bounded nonlinear least squares (control)
  libboost-test-dev                # unit tests
  libyaml-cpp-dev                  # scene files
  libbenchmark-dev                 # benchmarks
  nlohmann-json3-dev               # result files
  python3-matplotlib python3-numpy # figures of the validation report (validation/make_figures.py)
  python3-pytest                   # the Python tests
  python3-vtk9\|python3-paraview   # VTK's Python reader (tests/io); either package provides it
  pybind11-dev python3-dev         # the Python module (python/)
  libopenmpi-dev openmpi-bin       # MPI for rodlab study across ranks (optional at build time)
)
# Extra packages for one target only, e.g. `make fuzz` adds clang and libclang-rt-dev.
read -r -a extra <<< "${RODLAB_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
if command -v dpkg-query >/dev/null 2>&1; then
  installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'; }
  for entry in "${packages[@]}"; do
    # "a|b": any one of them will do (they conflict: python3-paraview, which make
    # paraview-figure needs, replaces python3-vtk9); the first is installed when none is
    IFS='|' read -r -a alternatives <<< "$entry"
    found=no
    for p in "${alternatives[@]}"; do
      if installed "$p"; then found=yes; break; fi
    done
    [ $found = yes ] || missing+=("${alternatives[0]}")
  done
else
  echo "bootstrap: dpkg-query not found (not Debian?); skipping package installation." >&2
fi

if [ ${#missing[@]} -gt 0 ]; then
  echo "bootstrap: installing missing Debian packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build_dir=${RODLAB_BUILD_DIR:-build}
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DRODLAB_WERROR=$werror >/dev/null
read -r -a targets <<< "${RODLAB_BUILD_TARGETS:-}"
if [ ${#targets[@]} -gt 0 ]; then
  cmake --build "$build_dir" -j "$(nproc)" --target "${targets[@]}"
else
  cmake --build "$build_dir" -j "$(nproc)"
fi
