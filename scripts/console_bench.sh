#!/usr/bin/env bash
# What the console costs the detection: runs `dotvision serve` on a synthetic
# site for SECONDS, once with no browser and once with two headless chromiums
# that each have every console page open (in iframes of one local page, so
# all pages poll at once), and prints per run the processed frame rate, the
# CPU frame time (pipeline + detection, p50/p99 over the last minute, from
# the status records), the latency p50/p99 over the whole run (serve's
# summary) and the CPU seconds serve used.
# At a venue the browsers run on the operators' laptops; here they share the
# machine's cores, so they run at nice $BROWSER_NICE (default 19) to stand in
# for another machine: what is measured is then what serving the console
# costs serve. BROWSER_IDLE=1 runs them under SCHED_IDLE as well (closer
# still to another machine); BROWSER_NICE=0 shows the worst case of
# browsers on the vision machine itself. SERVE_CPUS and BROWSER_CPUS (taskset
# lists, e.g. 0 and 1) give serve and the browsers cores of their own: the
# nearest this machine comes to browsers on the operators' laptops, since
# serve's console threads then compete with its cameras only. REPEAT=N
# alternates N runs of each, so that run-to-run spread shows.
#   scripts/console_bench.sh [BUILD_DIR] [SITE.yaml] [SECONDS]
set -euo pipefail
build=${1:-build}
site=${2:-config/site.example.yaml}
seconds=${3:-60}
cli=$build/dotvision
[ -x "$cli" ] || { echo "console_bench: no $cli (build the dotvision target)"; exit 2; }
command -v chromium >/dev/null || { echo "console_bench: chromium is not installed (scripts/setup.sh)"; exit 2; }
work=$(mktemp -d /tmp/dv_console_bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
port=$((18000 + $$ % 1000))

run() {  # run LABEL BROWSERS
  local label=$1 browsers=$2 pids=()
  ${SERVE_CPUS:+taskset -c $SERVE_CPUS} "$cli" serve "$site" --http "127.0.0.1:$port" --quiet --duration "$seconds" \
    --status-file "$work/status.json" >"$work/$label.out" 2>"$work/$label.log" &
  local serve=$!
  for _ in $(seq 100); do grep -q "console: http" "$work/$label.log" 2>/dev/null && break; sleep 0.2; done
  for b in $(seq "$browsers"); do
    {
      echo "<!doctype html><title>every console page</title>"
      for p in field camera colors calibration status settings; do
        echo "<iframe src=\"http://127.0.0.1:$port/$p.html\" width=1280 height=900></iframe>"
      done
    } >"$work/all$b.html"
    ${BROWSER_CPUS:+taskset -c $BROWSER_CPUS} ${BROWSER_IDLE:+chrt -i 0} nice -n "${BROWSER_NICE:-19}" chromium --headless --no-sandbox --disable-gpu --user-data-dir="$work/profile$b" \
      --window-size=1400,1000 --remote-debugging-port=0 "file://$work/all$b.html" >/dev/null 2>&1 &
    pids+=($!)
  done
  # serve's CPU time (user + system) near the end of the run, in seconds.
  sleep $((seconds - 3))
  local cpu
  cpu=$(awk -v hz="$(getconf CLK_TCK)" '{printf "%.1f", ($14 + $15) / hz}' "/proc/$serve/stat" 2>/dev/null || echo "?")
  wait "$serve"
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; wait "$p" 2>/dev/null || true; done
  echo "$label serve used $cpu CPU s in the first $((seconds - 3)) s"
  python3 - "$label" "$work/status.json" "$work/$label.out" <<'PY'
import json, re, sys
label, status_file, out = sys.argv[1:4]
s = json.load(open(status_file))
text = open(out).read()
for c in s["cameras"]:
    l = c["latency"]
    m = re.search(r"camera %d: .*?latency p50 ([\d.]+) ms, p99 ([\d.]+) ms" % c["camera_id"], text)
    print(f"{label:10s} camera {c['camera_id']}: {c['fps_out']:5.1f} fps processed; CPU frame time "
          f"pipeline {l['pipeline']['p50_ms']:.2f}/{l['pipeline']['p99_ms']:.2f} ms + detection "
          f"{l['detection']['p50_ms']:.2f}/{l['detection']['p99_ms']:.2f} ms (p50/p99, last minute); "
          f"latency over the run p50 {m.group(1) if m else '?'} ms, p99 {m.group(2) if m else '?'} ms; "
          f"dropped {c['frames']['dropped']}")
PY
  grep -h "serve: .* s" "$work/$label.out" | sed "s/^/$label /"
}

echo "console_bench: $site, $seconds s per run, $(nproc) cores, browsers at nice ${BROWSER_NICE:-19}" \
  "${SERVE_CPUS:+, serve on cpu $SERVE_CPUS}${BROWSER_CPUS:+, browsers on cpu $BROWSER_CPUS}"
for i in $(seq "${REPEAT:-1}"); do
  run none 0
  run browsers 2
done
