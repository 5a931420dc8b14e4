#!/usr/bin/env bash
# Runs one libFuzzer target: scripts/fuzz.sh TARGET SECONDS [libFuzzer flags...]
# or every target: scripts/fuzz.sh all SECONDS (two at a time, $DV_FUZZ_JOBS;
# exit 1 if any finds a crash, leak, timeout or sanitizer report).
# TARGET is a fuzz/fuzz_<TARGET>.cpp name (geometry_json, geometry_yaml,
# site_config, scene_yaml, ssl_log, detection_file, geometry_datagram,
# referee_datagram, image_decode, camera_buffer). Builds the target in build-fuzz (clang 14,
# ASan + UBSan + libFuzzer, see sanitizer_build.sh) and fuzzes it for SECONDS
# on a working copy of fuzz/corpus/TARGET (new inputs go to
# build-fuzz/fuzz/corpus/TARGET; crashes to build-fuzz/fuzz/artifacts/).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: scripts/fuzz.sh TARGET|all SECONDS [libFuzzer flags...]" >&2
  ls fuzz/fuzz_*.cpp | sed 's|fuzz/fuzz_||; s|\.cpp$||; s|^|  |' >&2
  exit 2
fi
target=$1 seconds=$2
shift 2
source scripts/sanitizer_build.sh
dir=$DV_SANITIZER_DIR
jobs=${DV_FUZZ_JOBS:-2}

if [ "$target" = all ]; then
  targets=$(ls fuzz/fuzz_*.cpp | sed 's|fuzz/fuzz_||; s|\.cpp$||')
  cmake --build "$dir" -j"$jobs" --target $(printf 'fuzz_%s ' $targets)
  mkdir -p "$dir/fuzz/logs"
  # Each run's log goes to build-fuzz/fuzz/logs/; a failed one is printed.
  failed=0
  for t in $targets; do echo "$t"; done |
    xargs -P "$jobs" -I{} sh -c 'DV_FUZZ_BUILT=1 scripts/fuzz.sh {} '"$seconds"' "$@" >"'"$dir"'/fuzz/logs/{}.log" 2>&1 || echo "FAILED {}"' sh "$@" \
    > "$dir/fuzz/logs/failed.txt" || true
  for t in $targets; do
    last=$(grep -E '^#[0-9]+' "$dir/fuzz/logs/$t.log" | tail -1 |
      sed -E 's/^#([0-9]+)[[:space:]]+[A-Z]+[[:space:]]+cov: ([0-9]+) ft: ([0-9]+).*/\1 runs, cov \2, ft \3/')
    printf '%-20s %s\n' "$t" "${last:-no run}"
  done
  if [ -s "$dir/fuzz/logs/failed.txt" ]; then
    for t in $(sed -n 's/^FAILED //p' "$dir/fuzz/logs/failed.txt"); do
      echo "---- fuzz_$t failed; the end of $dir/fuzz/logs/$t.log:" >&2
      tail -40 "$dir/fuzz/logs/$t.log" >&2
    done
    exit 1
  fi
  exit 0
fi

[ -f "fuzz/fuzz_${target}.cpp" ] || { echo "fuzz.sh: no target '${target}' (fuzz/fuzz_${target}.cpp)" >&2; exit 2; }
[ -n "${DV_FUZZ_BUILT:-}" ] || cmake --build "$dir" -j"$jobs" --target "fuzz_${target}"
work=$dir/fuzz/corpus/${target}
artifacts=$dir/fuzz/artifacts/${target}/
mkdir -p "$work" "$artifacts"
exec "$dir/fuzz/fuzz_${target}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 -artifact_prefix="$artifacts" "$@" "$work" "fuzz/corpus/${target}"
