// The Field page: the field to scale from /api/geometry, the cameras'
// footprints from /api/cameras, every camera's detections from
// /api/detections (5 times a second), a badge per camera from /api/status.
'use strict';
const kCameraColors = ['#ff4fd8', '#00e5ff', '#ffffff', '#b3ff00', '#ff9100', '#a78bfa', '#f472b6', '#22d3ee'];
const svgNs = 'http://www.w3.org/2000/svg';

function svgEl(name, attrs, parent) {
  const e = document.createElementNS(svgNs, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

// Field mm (x right, y up) -> SVG (y down).
const sx = (x) => x, sy = (y) => -y;

function drawField(geometry) {
  const f = geometry.field || {};
  const b = f.boundaryWidth || 300, L = f.fieldLength || 9000, W = f.fieldWidth || 6000;
  const svg = document.getElementById('field');
  svg.setAttribute('viewBox', `${-L / 2 - b} ${-W / 2 - b} ${L + 2 * b} ${W + 2 * b}`);
  const g = document.getElementById('lines');
  g.innerHTML = '';
  for (const l of f.fieldLines || [])
    svgEl('line', { class: 'line', x1: sx(l.p1.x), y1: sy(l.p1.y), x2: sx(l.p2.x), y2: sy(l.p2.y),
                    'stroke-width': l.thickness || 10 }, g);
  for (const a of f.fieldArcs || []) {
    const a1 = a.a1 || 0, a2 = a.a2 || 0, r = a.radius;
    const p = (t) => `${sx(a.center.x + r * Math.cos(t))} ${sy(a.center.y + r * Math.sin(t))}`;
    const large = Math.abs(a2 - a1) > Math.PI ? 1 : 0;
    // A full circle is two half arcs (an SVG arc cannot start and end at one point).
    const d = Math.abs(a2 - a1) >= 2 * Math.PI - 1e-6
      ? `M ${p(0)} A ${r} ${r} 0 1 0 ${p(Math.PI)} A ${r} ${r} 0 1 0 ${p(0)}`
      : `M ${p(a1)} A ${r} ${r} 0 ${large} 0 ${p(a2)}`;
    svgEl('path', { class: 'line', d, 'stroke-width': a.thickness || 10 }, g);
  }
}

function drawFootprints(cameras) {
  const g = document.getElementById('footprints');
  g.innerHTML = '';
  for (const c of cameras.cameras) {
    if (!c.footprint || c.footprint.length < 3) continue;
    svgEl('polygon', { class: 'footprint', 'data-camera': c.camera_id,
                       stroke: kCameraColors[c.camera_id % kCameraColors.length],
                       points: c.footprint.map(([x, y]) => `${sx(x)},${sy(y)}`).join(' ') }, g);
  }
}

function drawDetections(all) {
  const g = document.getElementById('detections');
  g.innerHTML = '';
  let robots = 0;
  for (const cam of all.cameras) {
    const d = cam.detection;
    if (!d) continue;
    const color = kCameraColors[cam.camera_id % kCameraColors.length];
    const cg = svgEl('g', { 'data-camera': cam.camera_id }, g);
    for (const [team, list] of [['yellow', d.robotsYellow || []], ['blue', d.robotsBlue || []]])
      for (const r of list) {
        ++robots;
        const rg = svgEl('g', { class: 'robot-group' }, cg);
        svgEl('circle', { class: `robot ${team}`, cx: sx(r.x), cy: sy(r.y), r: 90, style: `stroke: ${color}` }, rg);
        if (r.orientation !== undefined) {
          const t = r.orientation;
          svgEl('line', { class: 'heading', x1: sx(r.x), y1: sy(r.y), x2: sx(r.x + 90 * Math.cos(t)),
                          y2: sy(r.y + 90 * Math.sin(t)) }, rg);
        }
        if (r.robotId !== undefined)
          svgEl('text', { class: 'robot-id', x: sx(r.x), y: sy(r.y) + 0 }, rg).textContent = r.robotId;
      }
    for (const b of d.balls || [])
      svgEl('circle', { class: 'ball', cx: sx(b.x), cy: sy(b.y), r: 43, stroke: color }, cg);
  }
  document.getElementById('field').dataset.robots = robots;
}

function drawBadges(status) {
  const box = document.getElementById('badges');
  box.innerHTML = '';
  for (const c of status.cameras) {
    const b = document.createElement('span');
    b.className = `badge ${c.health}`;
    b.dataset.camera = c.camera_id;
    b.style.borderLeftColor = '';
    b.textContent = dv.badgeText(c);
    if (c.health_reason) b.title = c.health_reason;
    box.appendChild(b);
  }
}

async function fieldPage() {
  drawField(await dv.get('/api/geometry'));
  drawFootprints(await dv.get('/api/cameras'));
  dv.every(200, async () => drawDetections(await dv.get('/api/detections')));
  dv.every(1000, async () => drawBadges(await dv.get('/api/status')));
}
