#!/usr/bin/env bash
# Sourced by scripts/fuzz.sh and scripts/sanitize.sh: configures the
# sanitizer build in $DV_SANITIZER_DIR (default build-fuzz) once: clang 14,
# RelWithDebInfo, ASan + UBSan with libFuzzer's instrumentation (DV_FUZZ),
# so that the fuzz targets and the unit tests share its compiled libraries.
DV_SANITIZER_DIR=${DV_SANITIZER_DIR:-build-fuzz}
if [ ! -f "$DV_SANITIZER_DIR/CMakeCache.txt" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  cmake -S . -B "$DV_SANITIZER_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDV_FUZZ=ON \
    -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 "${launcher[@]}" >/dev/null
fi
# Any report ends the process with an error: UBSan is compiled without
# recovery, ASan stops at its first error, LSan fails the exit status.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:halt_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
