#!/usr/bin/env bash
# The unit suite under AddressSanitizer + UndefinedBehaviorSanitizer (docs/development.md):
#   scripts/sanitize.sh [CTEST_ARGS...]     default: -LE validation (the whole unit suite)
# Configures build-asan/ (-DRODLAB_SANITIZE=ON, -O1 -g as the sanitizers recommend: faster to
# compile than -O2, and the stack traces stay readable; no benchmarks; -Werror when CI=true), builds it and runs ctest with leak checking on and the LSan suppressions for
# OpenMPI's start-up (scripts/lsan-suppressions.txt). Any sanitizer report fails its test.
# Environment: SANITIZE_BUILD_DIR (build-asan), SANITIZE_JOBS (nproc).
set -euo pipefail
cd "$(dirname "$0")/.."

build_dir=${SANITIZE_BUILD_DIR:-build-asan}
jobs=${SANITIZE_JOBS:-$(nproc)}
werror=OFF
if [ "${CI:-}" = "true" ]; then werror=ON; fi
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" -DRODLAB_SANITIZE=ON \
  -DRODLAB_BUILD_BENCH=OFF -DRODLAB_WERROR=$werror "${launcher[@]}" >/dev/null
cmake --build "$build_dir" -j "$jobs"

ctest_args=("$@")
if [ ${#ctest_args[@]} -eq 0 ]; then ctest_args=(-LE validation); fi
cd "$build_dir"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
LSAN_OPTIONS=suppressions=$PWD/../scripts/lsan-suppressions.txt \
  ctest "${ctest_args[@]}" --output-on-failure -j "$jobs"
