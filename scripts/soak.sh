#!/usr/bin/env bash
# Soak: scripts/soak.sh MINUTES [OUT_DIR]  (default OUT_DIR build/soak)
# Runs `dotvision serve` on config/site.example.yaml (two synthetic cameras),
# their frame rate set to the league's 72 fps (SOAK_FPS to change it), with
# the console polled every second (/api/status, /api/detections, a camera
# snapshot) and samples the process every 10 s into OUT_DIR/soak.csv: RSS
# (VmRSS), open file descriptors, and per camera the input rate over the
# interval, the frame time p99 (arrival to packet) and the frames dropped,
# from the status file; and serve's CPU time per processed frame and the CPU
# the rest of the machine took (other processes and the hypervisor's steal,
# in cores), from /proc. Then it checks, and exits 1 if one fails:
#  - RSS from the first sample after 30 s to the last grows by at most 1 %
#    (runs under 10 minutes allow 4 MB more: allocator and cache warm-up is
#    still a large share of a short run);
#  - no drift in serve's work: its CPU time per processed frame, median of
#    the last third of the samples at most 1.5 x the first third's + 0.5 ms;
#  - no drift in p99: the median of the last third is at most 1.5 x the first
#    third's + 5 ms, per camera, unless the rest of the machine took more
#    CPU in the last third (a tenth of a core or more): a wall-clock time
#    follows the machine, and serve's own share is the check above;
#  - every camera delivers in every interval at 75 % of its median rate or
#    more, and serve keeps running; at most 1 % of the console polls fail;
#  - open file descriptors do not grow by more than 4.
# Charts: OUT_DIR/soak_memory.png (RSS, fds), soak_frames.png (p99) and
# soak_load.png (CPU per frame, other load).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 1 ]; then
  echo "usage: scripts/soak.sh MINUTES [OUT_DIR]" >&2
  exit 2
fi
minutes=$1
out=${2:-build/soak}
bin=./build/dotvision
[ -x "$bin" ] || { echo "soak: $bin missing: run scripts/setup.sh first" >&2; exit 2; }
command -v jq >/dev/null && command -v curl >/dev/null || { echo "soak: needs jq and curl" >&2; exit 2; }
mkdir -p "$out"
csv=$out/soak.csv status=$out/status.json log=$out/serve.log fails=$out/poll_failures
rm -f "$status" "$fails"
port=$((20000 + RANDOM % 20000))
url=http://127.0.0.1:$port

site=$out/site.yaml
sed -E "s/^( *fps: *)[0-9.]+/\1${SOAK_FPS:-72}/" config/site.example.yaml >"$site"
"$bin" serve "$site" --http "127.0.0.1:$port" --status-file "$status" >"$log" 2>&1 &
pid=$!
poller=
cleanup() {
  [ -n "$poller" ] && kill "$poller" 2>/dev/null || true
  kill "$pid" 2>/dev/null || true
}
trap cleanup EXIT

for _ in $(seq 120); do  # start-up: the status file and the console answer
  [ -s "$status" ] && curl -sf -o /dev/null "$url/api/status" && break
  kill -0 "$pid" 2>/dev/null || { echo "soak: serve exited at start:" >&2; tail -20 "$log" >&2; exit 1; }
  sleep 0.5
done
cameras=$(jq '.cameras | length' "$status")
first_camera=$(jq '.cameras[0].camera_id' "$status")

# The console as an operator's browser uses it, once a second.
(
  while kill -0 "$pid" 2>/dev/null; do
    for path in /api/status /api/detections "/api/cameras/$first_camera/snapshot.jpg"; do
      curl -sf -m 5 -o /dev/null "$url$path" || echo "$(date +%s) $path" >>"$fails"
    done
    sleep 1
  done
) &
poller=$!

header=t_s,rss_mb,fds,cpu_ms_frame,other_cores
for c in $(seq 0 $((cameras - 1))); do header+=",fps_in_$c,p99_ms_$c,dropped_$c"; done
echo "$header" >"$csv"
start=$(date +%s.%N)
end=$(( ${start%.*} + minutes * 60 ))
declare -a last_in
last_t=$start
for c in $(seq 0 $((cameras - 1))); do last_in[$c]=$(jq ".cameras[$c].frames.in" "$status"); done
hz=$(getconf CLK_TCK)
serve_ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }  # user + system, all threads
busy_ticks() { awk '/^cpu / {print $2 + $3 + $4 + $7 + $8 + $9}' /proc/stat; }  # all but idle, iowait
processed() { jq '[.cameras[].frames.processed] | add' "$status"; }
last_serve=$(serve_ticks) last_busy=$(busy_ticks) last_processed=$(processed)
while [ "$(date +%s)" -lt "$end" ]; do
  sleep 10
  kill -0 "$pid" 2>/dev/null || { echo "soak: serve died during the run:" >&2; tail -20 "$log" >&2; exit 1; }
  now=$(date +%s.%N)
  rss_kb=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status")
  fds=$(ls "/proc/$pid/fd" | wc -l)
  serve=$(serve_ticks) busy=$(busy_ticks) done_frames=$(processed)
  load=$(awk -v s="$((serve - last_serve))" -v b="$((busy - last_busy))" -v f="$((done_frames - last_processed))" \
    -v hz="$hz" -v t1="$now" -v t0="$last_t" 'BEGIN {printf "%.3f,%.2f", (f > 0 ? 1000 * s / hz / f : 0), (b - s) / hz / (t1 - t0)}')
  last_serve=$serve last_busy=$busy last_processed=$done_frames
  row="$(awk -v a="$now" -v b="$start" 'BEGIN {printf "%.1f", a - b}'),$(awk -v k="$rss_kb" 'BEGIN {printf "%.2f", k / 1024}'),$fds,$load"
  for c in $(seq 0 $((cameras - 1))); do
    read -r frames_in p99 dropped < <(jq -r ".cameras[$c] | \"\(.frames.in) \(.latency.total.p99_ms) \(.frames.dropped)\"" "$status")
    rate=$(awk -v a="$frames_in" -v b="${last_in[$c]}" -v t1="$now" -v t0="$last_t" 'BEGIN {printf "%.2f", (a - b) / (t1 - t0)}')
    last_in[$c]=$frames_in
    row+=",$rate,$(printf '%.2f' "$p99"),$dropped"
  done
  last_t=$now
  echo "$row" >>"$csv"
done
kill "$poller" 2>/dev/null || true
poller=
kill -TERM "$pid"
serve_rc=0
wait "$pid" || serve_rc=$?
trap - EXIT

polls=$(( ( $(date +%s) - ${start%.*} ) * 3 ))
failed_polls=$( [ -f "$fails" ] && wc -l <"$fails" || echo 0)
"$bin" plot "$csv" "$out/soak_memory.png" --columns rss_mb,fds --title "soak: serve, 2 synthetic cameras" \
  --ylabel "MB / count" >/dev/null || true
p99_columns=$(head -1 "$csv" | tr ',' '\n' | grep '^p99_ms_' | paste -sd,)
"$bin" plot "$csv" "$out/soak_frames.png" --columns "$p99_columns" --title "soak: frame time p99 (arrival to packet)" \
  --ylabel ms >/dev/null || true
"$bin" plot "$csv" "$out/soak_load.png" --columns cpu_ms_frame,other_cores \
  --title "soak: serve's CPU ms per frame, other load (cores)" --ylabel "ms / cores" >/dev/null || true

# The checks, on the CSV.
slack=$([ "$minutes" -lt 10 ] && echo 4 || echo 0)
awk -F, -v cameras="$cameras" -v slack="$slack" -v polls="$polls" -v failed="$failed_polls" -v rc="$serve_rc" '
  NR == 1 { next }
  { n++; t[n] = $1; rss[n] = $2; fd[n] = $3; work[0, n] = $4; other[0, n] = $5
    for (c = 0; c < cameras; c++) { rate[c, n] = $(6 + 3 * c); p99[c, n] = $(7 + 3 * c) } }
  function median(arr, c, from, to,   i, k, v, tmp) {
    k = 0; for (i = from; i <= to; i++) tmp[++k] = arr[c, i]
    for (i = 2; i <= k; i++) { v = tmp[i]; j = i - 1; while (j > 0 && tmp[j] > v) { tmp[j + 1] = tmp[j]; j-- } tmp[j + 1] = v }
    return k % 2 ? tmp[(k + 1) / 2] : (tmp[k / 2] + tmp[k / 2 + 1]) / 2
  }
  END {
    bad = 0
    if (n < 3) { print "soak: only " n " samples"; exit 1 }
    first = 1; while (first < n && t[first] < 30) first++
    limit = rss[first] * 0.01 + slack
    printf "soak: %d samples over %d s; RSS %.1f MB at %d s -> %.1f MB at %d s (%+.2f MB, %+.2f %%; limit %.2f MB)\n", \
      n, t[n], rss[first], t[first], rss[n], t[n], rss[n] - rss[first], 100 * (rss[n] - rss[first]) / rss[first], limit
    if (rss[n] - rss[first] > limit) { print "soak: FAIL: memory grew"; bad = 1 }
    printf "soak: open fds %d -> %d\n", fd[first], fd[n]
    if (fd[n] > fd[first] + 4) { print "soak: FAIL: file descriptors grew"; bad = 1 }
    third = int((n - first + 1) / 3); if (third < 1) third = 1
    wa = median(work, 0, first, first + third - 1); wb = median(work, 0, n - third + 1, n)
    oa = median(other, 0, first, first + third - 1); ob = median(other, 0, n - third + 1, n)
    printf "soak: serve CPU per frame %.2f ms (first third) -> %.2f ms (last third); the rest of the machine %.2f -> %.2f cores\n", wa, wb, oa, ob
    if (wb > 1.5 * wa + 0.5) { print "soak: FAIL: serve'"'"'s CPU time per frame drifted"; bad = 1 }
    busier = ob >= oa + 0.1
    for (c = 0; c < cameras; c++) {
      a = median(p99, c, first, first + third - 1); b = median(p99, c, n - third + 1, n)
      m = median(rate, c, 1, n); low = m; for (i = 1; i <= n; i++) if (rate[c, i] < low) low = rate[c, i]
      printf "soak: camera %d: p99 median %.2f ms (first third) -> %.2f ms (last third); input %.1f fps median, lowest interval %.1f\n", c, a, b, m, low
      if (b > 1.5 * a + 5 && busier) print "soak: camera " c ": p99 rose while the rest of the machine took more CPU; not counted"
      else if (b > 1.5 * a + 5) { print "soak: FAIL: camera " c " p99 drifted"; bad = 1 }
      if (low < 0.75 * m || m <= 0) { print "soak: FAIL: camera " c " stopped delivering at its rate"; bad = 1 }
    }
    printf "soak: console polls failed: %d of about %d\n", failed, polls
    if (failed > polls / 100) { print "soak: FAIL: console polls failed"; bad = 1 }
    if (rc != 0) { print "soak: FAIL: serve exited with " rc " on SIGTERM"; bad = 1 }
    exit bad
  }' "$csv"
