#!/usr/bin/env bash
# Runs one libFuzzer target: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]
# TARGET is a fuzz/fuzz_<TARGET>.cpp name (geometry_json, geometry_yaml,
# site_config, scene_yaml, ssl_log, detection_file, geometry_datagram,
# referee_datagram, image_decode). Configures build-fuzz with clang 14
# (ASan + UBSan + libFuzzer), builds the target and fuzzes it for SECONDS on
# a working copy of fuzz/corpus/TARGET (new inputs go to
# build-fuzz/fuzz/corpus/TARGET; crashes to build-fuzz/fuzz/artifacts/).
# All targets, DV_FUZZ_SECONDS each: ctest --test-dir build-fuzz -L fuzz
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]" >&2
  ls fuzz/fuzz_*.cpp | sed 's|fuzz/fuzz_||; s|\.cpp$||; s|^|  |' >&2
  exit 2
fi
target=$1 seconds=$2
shift 2
[ -f "fuzz/fuzz_${target}.cpp" ] || { echo "fuzz.sh: no target '${target}' (fuzz/fuzz_${target}.cpp)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDV_FUZZ=ON \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 "${launcher[@]}" >/dev/null
fi
cmake --build build-fuzz -j"${DV_FUZZ_JOBS:-2}" --target "fuzz_${target}"
work=build-fuzz/fuzz/corpus/${target}
artifacts=build-fuzz/fuzz/artifacts/${target}/
mkdir -p "$work" "$artifacts"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
exec "build-fuzz/fuzz/fuzz_${target}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 -artifact_prefix="$artifacts" "$@" "$work" "fuzz/corpus/${target}"
