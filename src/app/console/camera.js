// The Camera page: one camera's newest frame as a JPEG (a new one as soon as
// the last one loaded, at most 4 a second). The picture is the raw frame or
// one on the rectified field grid (rectified, chroma, gradient dot product,
// blob score: the server's own pipeline run on the frame); over it the
// blobs, the field lines projected through the calibration and the
// detections, all drawn on the server. Hovering shows the field point under
// the mouse: on the raw frame /api/cameras/ID/field_point answers for the
// image pixel; on the grid the grid of /api/cameras/ID/grid maps the cell.
'use strict';
const kMaxFps = 4;

// Where the mouse is on the picture, in the picture's full-size pixels
// (centers at integers): `size` is the full picture's width and height.
function pictureAt(ev, img, size) {
  return [(ev.offsetX / img.clientWidth) * size[0] - 0.5, (ev.offsetY / img.clientHeight) * size[1] - 0.5];
}

async function cameraPage() {
  const cams = (await dv.get('/api/cameras')).cameras;
  const select = document.getElementById('camera');
  for (const c of cams) select.add(new Option(`camera ${c.camera_id}`, c.camera_id));
  const wanted = new URLSearchParams(location.search).get('camera');
  if (wanted !== null) select.value = wanted;
  const img = document.getElementById('snapshot');
  const hover = document.getElementById('hover');
  const current = () => cams.find((c) => String(c.camera_id) === select.value) || cams[0];
  const base = () => document.querySelector('input[name=base]:checked').value;
  let grid = null;  // the grid of the picture on the page, when it is a grid picture
  const loadGrid = async () => {
    grid = base() === 'raw' ? null : await dv.get(`/api/cameras/${current().camera_id}/grid`);
  };

  let started = 0;
  const next = () => {
    const layers = [base()];
    for (const name of ['blobs', 'lines', 'detections'])
      if (document.getElementById('layer-' + name).checked) layers.push(name);
    const width = Math.max(160, Math.min(960, Math.round(document.querySelector('main').clientWidth)));
    started = performance.now();
    img.dataset.layers = layers.join(',');
    img.src = `/api/cameras/${current().camera_id}/snapshot.jpg?layer=${layers.join(',')}&width=${width}&t=${Date.now()}`;
  };
  // One request at a time: a change replaces the pending one.
  let timer = 0;
  const schedule = (ms) => { clearTimeout(timer); timer = setTimeout(next, ms); };
  img.addEventListener('load', () => {
    img.dataset.loaded = Number(img.dataset.loaded || 0) + 1;
    schedule(Math.max(0, 1000 / kMaxFps - (performance.now() - started)));
  });
  img.addEventListener('error', () => schedule(1000));
  const changed = async () => {
    hover.textContent = 'hover over the image for field coordinates';
    try { await loadGrid(); } catch (e) { grid = null; }
    schedule(0);
  };
  select.addEventListener('change', changed);
  for (const r of document.querySelectorAll('input[name=base]')) r.addEventListener('change', changed);
  next();
  // An accepted calibration moves the grid.
  dv.every(5000, async () => { if (base() !== 'raw') await loadGrid(); });

  let asking = false;
  img.addEventListener('mousemove', async (ev) => {
    const c = current();
    if (base() !== 'raw') {
      if (!grid) return;
      const [gx, gy] = pictureAt(ev, img, [grid.width, grid.height]);
      const x = grid.x0_mm + gx * grid.mm_per_cell, y = grid.y0_mm - gy * grid.mm_per_cell;
      hover.textContent = `grid cell (${gx.toFixed(0)}, ${gy.toFixed(0)}) → field x ${x.toFixed(0)} mm, ` +
                          `y ${y.toFixed(0)} mm (on the plane z = ${grid.plane_height_mm.toFixed(0)} mm)`;
      hover.dataset.field = `${x.toFixed(0)},${y.toFixed(0)}`;
      return;
    }
    if (asking || !c.image_width) return;
    asking = true;
    const [u, v] = pictureAt(ev, img, [c.image_width, c.image_height]);
    try {
      const p = await dv.get(`/api/cameras/${c.camera_id}/field_point?u=${u.toFixed(1)}&v=${v.toFixed(1)}`);
      hover.textContent = p.x === null
        ? `pixel (${u.toFixed(0)}, ${v.toFixed(0)}): ${p.why}`
        : `pixel (${u.toFixed(0)}, ${v.toFixed(0)}) → field x ${p.x.toFixed(0)} mm, y ${p.y.toFixed(0)} mm`;
      hover.dataset.field = p.x === null ? '' : `${p.x.toFixed(0)},${p.y.toFixed(0)}`;
    } finally { asking = false; }
  });

  dv.every(1000, async () => {
    const s = (await dv.get('/api/status')).cameras.find((c) => c.camera_id === current().camera_id);
    if (s) document.getElementById('badge').textContent = dv.badgeText(s);
  });
}
