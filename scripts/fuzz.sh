#!/usr/bin/env bash
# Fuzzes the scene loader and the --set overrides with libFuzzer (docs/development.md):
#   scripts/fuzz.sh [RUNS] [TARGET...]     RUNS inputs per target (default 1000000);
#                                          TARGETs: scene_loader overrides (default both)
# Configures build-fuzz/ with clang (-DRODLAB_FUZZ=ON: ASan + UBSan + libFuzzer), builds the
# targets and runs each for RUNS inputs with a 1 s limit per input. The corpus grows in
# build-fuzz/corpus/<target>/ (seeded from scenes/, tests/data/scenes/ and fuzz/corpus/);
# a finding is written to build-fuzz/findings/ and makes the script exit 1.
# Environment: FUZZ_BUILD_DIR (build-fuzz), FUZZ_JOBS (nproc), FUZZ_MAX_LEN (4096),
# FUZZ_RSS_LIMIT_MB (2048), CXX (clang++), FUZZ_WERROR (OFF; CI sets ON).
set -euo pipefail
cd "$(dirname "$0")/.."

runs=${1:-1000000}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(scene_loader overrides); fi

cxx=${CXX:-clang++}
if ! command -v "$cxx" >/dev/null 2>&1 || ! "$cxx" --version | grep -q clang; then
  echo "fuzz.sh: needs clang++ with libFuzzer (Debian: apt-get install clang)" >&2
  exit 2
fi
cc=${CC:-${cxx/clang++/clang}}
build_dir=${FUZZ_BUILD_DIR:-build-fuzz}
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_C_COMPILER="$cc" "${launcher[@]}" -DRODLAB_FUZZ=ON -DRODLAB_BUILD_TESTS=OFF \
  -DRODLAB_BUILD_BENCH=OFF -DRODLAB_WERROR="${FUZZ_WERROR:-OFF}" >/dev/null
cmake --build "$build_dir" -j "${FUZZ_JOBS:-$(nproc)}" \
  --target "${targets[@]/#/fuzz_}"

seeds_scene_loader=(scenes tests/data/scenes)
seeds_overrides=(fuzz/corpus/overrides)
status=0
for t in "${targets[@]}"; do
  corpus="$build_dir/corpus/$t"
  findings="$build_dir/findings/$t"
  mkdir -p "$corpus" "$findings"
  seeds_var="seeds_${t}[@]"
  seeds=()
  for d in "${!seeds_var}"; do [ -d "$d" ] && seeds+=("$d"); done
  echo "== fuzz_$t: $runs inputs"
  # ASan's leak check stays on; UBSan reports are fatal (-fno-sanitize-recover).
  if ! "$build_dir/bin/fuzz_$t" -runs="$runs" -timeout=1 -max_len="${FUZZ_MAX_LEN:-4096}" \
      -rss_limit_mb="${FUZZ_RSS_LIMIT_MB:-2048}" -dict=fuzz/scene.dict -print_final_stats=1 \
      -artifact_prefix="$findings/" "$corpus" "${seeds[@]}"; then
    echo "fuzz.sh: fuzz_$t found a problem: see $findings/" >&2
    status=1
  fi
done
exit $status
