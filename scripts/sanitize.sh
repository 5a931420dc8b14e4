#!/usr/bin/env bash
# Builds the unit tests with AddressSanitizer + UndefinedBehaviorSanitizer
# (build-fuzz, shared with the fuzz targets: see sanitizer_build.sh) and runs
# them (ctest label unit); any sanitizer report fails its test and the script.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitizer_build.sh
cmake --build "$DV_SANITIZER_DIR" -j"$(nproc)" --target dotvision_unit_tests
ctest --test-dir "$DV_SANITIZER_DIR" -L unit --output-on-failure -j"$(nproc)"
