// The Status page: serve's status document (/api/status) once a second as a
// table, a line per camera, with the total latency's p50/p99 of the last
// minute as a small chart, and each camera's newest problem.
'use strict';
const latencyHistory = {};  // camera id -> [{p50, p99}], the last 60 seconds

function spark(canvas, points) {
  const ctx = canvas.getContext('2d');
  canvas.width = 160; canvas.height = 32;
  ctx.clearRect(0, 0, 160, 32);
  const top = Math.max(1, ...points.map((p) => p.p99));
  for (const [key, color] of [['p99', '#d29922'], ['p50', '#4fa3ff']]) {
    ctx.strokeStyle = color;
    ctx.beginPath();
    points.forEach((p, i) => {
      const x = i * 160 / 60, y = 31 - Math.max(0, p[key]) / top * 30;
      i ? ctx.lineTo(x, y) : ctx.moveTo(x, y);
    });
    ctx.stroke();
  }
}

function row(c) {
  const f = c.frames, l = c.latency;
  const pair = (x) => `${dv.fixed(x.p50_ms, 2)} / ${dv.fixed(x.p99_ms, 2)}`;
  return `<td>${c.camera_id}</td><td class="health-${c.health}" title="${c.health_reason || ''}">${c.health}</td>` +
    `<td>${c.source_state}</td><td>${dv.fixed(c.fps_in, 1)} / ${dv.fixed(c.fps_out, 1)}</td>` +
    `<td>${pair(l.total)}</td><td><canvas class="spark"></canvas></td><td>${pair(l.pipeline)}</td>` +
    `<td>${pair(l.detection)}</td><td>${f.dropped}</td><td>${f.skipped}</td><td>${c.losses}</td>` +
    `<td>${c.reconnects}</td><td>${dv.fixed(c.per_frame.robots, 1)}</td><td>${dv.fixed(c.per_frame.balls, 1)}</td>`;
}

// serve's recent log lines (/api/log), newest last; warnings in color.
const logLines = [];
let logSeq = 0;
function showLog() {
  const only = document.getElementById('warnings-only').checked;
  const box = document.getElementById('log');
  box.innerHTML = '';
  for (const l of logLines.filter((x) => !only || x.warning).slice(-100)) {
    const div = document.createElement('div');
    div.className = l.warning ? 'log-warning' : '';
    div.textContent = `${new Date(l.t * 1000).toLocaleTimeString()}  ${l.text}`;
    box.appendChild(div);
  }
}

async function statusPage() {
  document.getElementById('warnings-only').addEventListener('change', showLog);
  dv.every(2000, async () => {
    const got = (await dv.get(`/api/log?after=${logSeq}`)).lines;
    if (!got.length) return;
    logLines.push(...got);
    logSeq = got[got.length - 1].seq;
    if (logLines.length > 500) logLines.splice(0, logLines.length - 500);
    showLog();
  });
  dv.every(1000, async () => {
    const s = await dv.get('/api/status');
    document.getElementById('config').textContent = `config ${s.config}` +
      (s.teams && (s.teams.yellow || s.teams.blue) ? ` · yellow ${s.teams.yellow}, blue ${s.teams.blue}` : '');
    const body = document.querySelector('#status tbody');
    body.innerHTML = '';
    const problems = [];
    for (const c of s.cameras) {
      const h = (latencyHistory[c.camera_id] = latencyHistory[c.camera_id] || []);
      h.push({ p50: c.latency.total.p50_ms, p99: c.latency.total.p99_ms });
      if (h.length > 60) h.shift();
      const tr = document.createElement('tr');
      tr.dataset.camera = c.camera_id;
      tr.innerHTML = row(c);
      body.appendChild(tr);
      spark(tr.querySelector('canvas'), h);
      if (c.last_problem) problems.push(`camera ${c.camera_id}: ${c.last_problem}`);
    }
    document.getElementById('problems').textContent = problems.join('\n') || 'none';
  });
}
