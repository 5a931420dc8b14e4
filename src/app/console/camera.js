// The Camera page: one camera's newest frame as a JPEG (a new one as soon as
// the last one loaded, at most 4 a second), with the field lines projected
// through the calibration and the detections drawn on the server; hovering
// asks /api/cameras/ID/field_point for the field point under the mouse.
'use strict';
const kMaxFps = 4;

async function cameraPage() {
  const cams = (await dv.get('/api/cameras')).cameras;
  const select = document.getElementById('camera');
  for (const c of cams) select.add(new Option(`camera ${c.camera_id}`, c.camera_id));
  const wanted = new URLSearchParams(location.search).get('camera');
  if (wanted !== null) select.value = wanted;
  const img = document.getElementById('snapshot');
  const current = () => cams.find((c) => String(c.camera_id) === select.value) || cams[0];

  let started = 0;
  const next = () => {
    const layers = ['raw'];
    if (document.getElementById('layer-lines').checked) layers.push('lines');
    if (document.getElementById('layer-detections').checked) layers.push('detections');
    const width = Math.max(160, Math.min(960, Math.round(document.querySelector('main').clientWidth)));
    started = performance.now();
    img.src = `/api/cameras/${current().camera_id}/snapshot.jpg?layer=${layers.join(',')}&width=${width}&t=${Date.now()}`;
  };
  const again = () => setTimeout(next, Math.max(0, 1000 / kMaxFps - (performance.now() - started)));
  img.addEventListener('load', () => { img.dataset.loaded = (Number(img.dataset.loaded || 0) + 1); again(); });
  img.addEventListener('error', () => setTimeout(next, 1000));
  select.addEventListener('change', next);
  next();

  let asking = false;
  img.addEventListener('mousemove', async (ev) => {
    const c = current();
    if (asking || !c.image_width) return;
    asking = true;
    const u = ev.offsetX / img.clientWidth * c.image_width, v = ev.offsetY / img.clientHeight * c.image_height;
    try {
      const p = await dv.get(`/api/cameras/${c.camera_id}/field_point?u=${u.toFixed(1)}&v=${v.toFixed(1)}`);
      document.getElementById('hover').textContent = p.x === null
        ? `pixel (${u.toFixed(0)}, ${v.toFixed(0)}): ${p.why}`
        : `pixel (${u.toFixed(0)}, ${v.toFixed(0)}) → field x ${p.x.toFixed(0)} mm, y ${p.y.toFixed(0)} mm`;
    } finally { asking = false; }
  });

  dv.every(1000, async () => {
    const s = (await dv.get('/api/status')).cameras.find((c) => c.camera_id === current().camera_id);
    if (s) document.getElementById('badge').textContent = dv.badgeText(s);
  });
}
