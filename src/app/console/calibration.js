// The Calibration page: runs the automatic calibration (or the four-point
// one, on known field points the operator picked on the image: the lines'
// crossings and corners from the geometry) on a camera's newest frame on the server, polls its state, shows the
// frame with the segments found and the model lines through the result, the
// quality figures and the verdict; Accept makes it the camera's calibration.
'use strict';

function figureRows(j) {
  const r = j.report || {};
  const rows = [['state', j.state + (j.error ? ': ' + j.error : '')]];
  if (r.verdict) rows.push(['verdict', r.verdict.passed ? 'passed' : 'refused: ' + r.verdict.reason]);
  if (r.mode) rows.push(['mode', r.mode], ['seconds', dv.fixed(r.seconds, 1)]);
  if (r.lines) rows.push(['line groups found / used', `${r.lines.groups_found} / ${r.lines.groups_used}`],
                         ['line pixels', r.lines.line_pixels]);
  const m = r.measures;
  if (m) rows.push(['overlap ratio', dv.fixed(m.overlap_ratio, 3)], ['model support', dv.fixed(m.model_support, 3)],
                   ['mean distance', `${dv.fixed(m.mean_distance_px, 2)} px · ${dv.fixed(m.mean_distance_mm, 2)} mm`]);
  const p = r.parameters;
  if (p) rows.push(['focal length px', dv.fixed(p.focal_length_px, 1)],
                   ['position mm', p.position_mm.map((v) => v.toFixed(0)).join(', ')],
                   ['tilt / heading deg', `${dv.fixed(p.tilt_deg, 1)} / ${p.heading_deg.toFixed(1)}`],
                   ['distortion', p.distortion.toFixed(4)]);
  if (r.symmetry) rows.push(['symmetry', `${r.symmetry.basis}: ${r.symmetry.reason}`]);
  return rows;
}

// The field points an operator can find in an image: where two painted lines
// (segments of the geometry) cross or meet, and where the center circle
// meets a line; each named by its lines and rounded to the millimetre.
function knownFieldPoints(field) {
  const lines = field.fieldLines || [], arcs = field.fieldArcs || [], out = [];
  const add = (x, y, name) => {
    x = Math.round(x) + 0, y = Math.round(y) + 0;  // + 0: no -0
    if (!out.some((p) => Math.hypot(p.x - x, p.y - y) < 5)) out.push({ x, y, name });
  };
  const tol = 1;  // mm beyond a segment's end that still counts as meeting it
  for (let i = 0; i < lines.length; ++i)
    for (let j = i + 1; j < lines.length; ++j) {
      const a = lines[i], b = lines[j];
      const dx1 = a.p2.x - a.p1.x, dy1 = a.p2.y - a.p1.y, dx2 = b.p2.x - b.p1.x, dy2 = b.p2.y - b.p1.y;
      const den = dx1 * dy2 - dy1 * dx2;
      const len1 = Math.hypot(dx1, dy1), len2 = Math.hypot(dx2, dy2);
      if (Math.abs(den) < 1e-9 * len1 * len2) continue;  // parallel
      const t = ((b.p1.x - a.p1.x) * dy2 - (b.p1.y - a.p1.y) * dx2) / den;
      const u = ((b.p1.x - a.p1.x) * dy1 - (b.p1.y - a.p1.y) * dx1) / den;
      if (t * len1 < -tol || (t - 1) * len1 > tol || u * len2 < -tol || (u - 1) * len2 > tol) continue;
      add(a.p1.x + t * dx1, a.p1.y + t * dy1, `${a.name} × ${b.name}`);
    }
  for (const c of arcs)
    for (const l of lines) {
      // |p1 + t d - center| = r along the segment
      const dx = l.p2.x - l.p1.x, dy = l.p2.y - l.p1.y, fx = l.p1.x - c.center.x, fy = l.p1.y - c.center.y;
      const A = dx * dx + dy * dy, B = 2 * (fx * dx + fy * dy), C = fx * fx + fy * fy - c.radius * c.radius;
      const disc = B * B - 4 * A * C;
      if (A === 0 || disc <= 0) continue;
      for (const t of [(-B - Math.sqrt(disc)) / (2 * A), (-B + Math.sqrt(disc)) / (2 * A)]) {
        if (t < 0 || t > 1) continue;
        const x = l.p1.x + t * dx, y = l.p1.y + t * dy;
        const a1 = c.a1 || 0, a2 = c.a2 || 0;
        let ang = Math.atan2(y - c.center.y, x - c.center.x);
        while (ang < a1) ang += 2 * Math.PI;
        if (ang - a1 <= a2 - a1 + 1e-6) add(x, y, `${c.name} × ${l.name}`);
      }
    }
  return out.sort((p, q) => p.x - q.x || q.y - p.y);
}

async function calibrationPage() {
  const cams = (await dv.get('/api/cameras')).cameras;
  const select = document.getElementById('camera');
  for (const c of cams) select.add(new Option(`camera ${c.camera_id}`, c.camera_id));
  const wanted = new URLSearchParams(location.search).get('camera');
  if (wanted !== null) select.value = wanted;
  const id = () => select.value;
  const img = document.getElementById('image');
  const notes = document.getElementById('notes');
  let shown = '';  // the state whose image is on the page
  const picked = [];  // the four-point fallback's points: {x, y (field mm), name, u, v (image px)}

  const show = (j) => {
    document.getElementById('state').textContent = `camera ${j.camera_id}: ${j.state}` +
      (j.report && j.report.verdict ? (j.report.verdict.passed ? ' · passed' : ' · refused') : '');
    document.getElementById('state').dataset.state = j.state;
    document.getElementById('accept').disabled = !(j.state === 'done' && j.passed);
    document.getElementById('reject').disabled = j.state !== 'done';
    const body = document.querySelector('#figures tbody');
    body.innerHTML = '';
    for (const [k, v] of figureRows(j)) {
      const tr = document.createElement('tr');
      tr.innerHTML = `<td></td><td></td>`;
      tr.children[0].textContent = k;
      tr.children[1].textContent = v;
      body.appendChild(tr);
    }
    const key = j.camera_id + ':' + j.state;
    if (key === shown) return;
    shown = key;
    img.dataset.size = (j.image_size || []).join('x');
    img.src = j.state === 'none' || j.state === 'running'
      ? `/api/cameras/${j.camera_id}/snapshot.jpg?layer=raw&width=960&t=${Date.now()}`
      : `/api/cameras/${j.camera_id}/calibration/overlay.jpg?width=960&t=${Date.now()}`;
  };
  const refresh = async () => show(await dv.get(`/api/cameras/${id()}/calibration`));
  select.addEventListener('change', () => { shown = ''; refresh(); });
  dv.every(1000, refresh);

  document.getElementById('run').addEventListener('click', async () => {
    const body = {};
    const region = document.getElementById('region').value, near = document.getElementById('near').value.trim();
    const height = Number(document.getElementById('height').value);
    if (region) body.region = region;
    if (near) body.near = near;
    if (height > 0) body.camera_height = height;
    if (picked.length) body.points = picked.map((p) => [p.x, p.y, p.u, p.v]);
    const r = await dv.send('POST', `/api/cameras/${id()}/calibrate`, JSON.stringify(body));
    notes.textContent = r.status === 202 ? 'running on the newest frame…' : r.body.error;
    if (r.status === 202) { shown = ''; show(r.body); }
  });
  for (const [button, path] of [['accept', 'accept'], ['reject', 'reject']])
    document.getElementById(button).addEventListener('click', async () => {
      const r = await dv.send('POST', `/api/cameras/${id()}/calibration/${path}`, '{}');
      notes.textContent = r.status === 200 ? (r.body.notes || ['rejected']).join('\n') : r.body.error;
      refresh();
    });
  // The four-point fallback: choose a known field point, click where the
  // image shows it (full-size image px, centers at integers).
  const known = knownFieldPoints((await dv.get('/api/geometry')).field || {});
  const knownSelect = document.getElementById('known');
  known.forEach((p, i) => knownSelect.add(new Option(`${p.name} (${p.x}, ${p.y})`, i)));
  const view = document.getElementById('view');
  const showPicked = () => {
    const body = document.querySelector('#picked tbody');
    body.innerHTML = '';
    for (const m of view.querySelectorAll('.pick-mark')) m.remove();
    const [w, h] = imageSize();
    picked.forEach((p, i) => {
      const tr = document.createElement('tr');
      tr.innerHTML = '<td></td><td></td><td></td><td><button class="secondary">remove</button></td>';
      tr.children[0].textContent = p.name;
      tr.children[1].textContent = `${p.x}, ${p.y}`;
      tr.children[2].textContent = `${p.u.toFixed(1)}, ${p.v.toFixed(1)}`;
      tr.querySelector('button').addEventListener('click', () => { picked.splice(i, 1); showPicked(); });
      body.appendChild(tr);
      if (!w) return;
      const mark = document.createElement('div');
      mark.className = 'pick-mark';
      mark.style.left = `${((p.u + 0.5) / w) * 100}%`;
      mark.style.top = `${((p.v + 0.5) / h) * 100}%`;
      mark.innerHTML = '<span></span>';
      mark.firstChild.textContent = `${p.x}, ${p.y}`;
      view.appendChild(mark);
    });
    document.getElementById('picked').dataset.count = picked.length;
  };
  const imageSize = () => {
    const [w, h] = (img.dataset.size || '').split('x').map(Number);
    const c = cams.find((x) => String(x.camera_id) === id()) || {};
    return [w || c.image_width, h || c.image_height];
  };
  document.getElementById('clear-points').addEventListener('click', () => { picked.length = 0; showPicked(); });
  select.addEventListener('change', () => { picked.length = 0; showPicked(); });
  img.addEventListener('click', (ev) => {
    const [fw, fh] = imageSize();
    const k = known[Number(knownSelect.value)];
    if (!fw || !k) return;
    document.getElementById('picker').open = true;
    const u = Math.max(0, (ev.offsetX / img.clientWidth) * fw - 0.5);
    const v = Math.max(0, (ev.offsetY / img.clientHeight) * fh - 0.5);
    const again = picked.findIndex((p) => p.x === k.x && p.y === k.y);
    if (again >= 0) picked.splice(again, 1);  // clicked anew: the later click counts
    picked.push({ ...k, u, v });
    // On to the next point not picked yet.
    for (let i = 1; i <= known.length; ++i) {
      const n = (Number(knownSelect.value) + i) % known.length;
      if (!picked.some((p) => p.x === known[n].x && p.y === known[n].y)) { knownSelect.value = n; break; }
    }
    showPicked();
  });
}
