// The Calibration page: runs the automatic calibration (or the four-point
// one) on a camera's newest frame on the server, polls its state, shows the
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
    const lines = document.getElementById('points').value.split('\n').map((l) => l.trim()).filter((l) => l);
    if (lines.length) {
      body.points = lines.map((l) => l.split(/[,=\s]+/).map(Number));
    }
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
  // The four-point fallback: a click adds the pixel under it, full-size.
  img.addEventListener('click', (ev) => {
    const [w, h] = (img.dataset.size || '').split('x').map(Number);
    const c = cams.find((x) => String(x.camera_id) === id()) || {};
    const fw = w || c.image_width, fh = h || c.image_height;
    if (!fw) return;
    const u = ev.offsetX / img.clientWidth * fw, v = ev.offsetY / img.clientHeight * fh;
    const area = document.getElementById('points');
    area.closest('details').open = true;
    area.value += (area.value && !area.value.endsWith('\n') ? '\n' : '') + `X,Y=${u.toFixed(1)},${v.toFixed(1)}`;
  });
}
