#!/usr/bin/env bash
# Every test, as CI runs it (.ci/run calls this): setup and the test suite,
# then the unit tests under ASan + UBSan (scripts/sanitize.sh), each fuzz
# target for 60 s (scripts/fuzz.sh all 60) and a 2-minute soak of serve
# (scripts/soak.sh 2). Each step's time is printed; any failure fails the
# run, after the remaining steps have run.
set -uo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh || exit 1
failed=()
step() {
  local name=$1 begin=$SECONDS
  shift
  echo "==== $name: $*"
  "$@" || failed+=("$name")
  echo "==== $name: $((SECONDS - begin)) s"
}
step tests ctest --test-dir build --output-on-failure -j2
step sanitizers bash scripts/sanitize.sh
step fuzz bash scripts/fuzz.sh all "${DV_FUZZ_SECONDS:-60}"
step soak bash scripts/soak.sh 2
if [ ${#failed[@]} -gt 0 ]; then
  echo "FAILED: ${failed[*]}" >&2
  exit 1
fi
echo "all passed"
