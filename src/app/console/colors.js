// The Colors page: /api/cameras/ID/colors twice a second, drawn on the chroma
// plane (the chromaticity triangle seen along the gray axis): every recent
// blob as a dot in its own color, the learned classes as rings, the pairs the
// detector must separate joined by a line with their distance.
'use strict';
const kClassStyle = { yellow: '#ffd92e', blue: '#3a8bff', green: '#3fb950', pink: '#ff5fd2', orange: '#ff8c1a',
                      field: '#1d8f3a', white: '#ffffff' };
const kPairs = [['yellow', 'blue', 'yellow_blue'], ['green', 'pink', 'green_pink'], ['orange', 'field', 'orange_field']];

// Chromaticity (sums to ~300) -> the plane normal to the gray axis, gray at 0.
function plane(c) {
  return [(c[0] - c[1]) / Math.SQRT2, -(c[0] + c[1] - 2 * c[2]) / Math.sqrt(6)];
}
function rgbOf(c) {
  const m = Math.max(c[0], c[1], c[2], 1);
  return `rgb(${c.map((v) => Math.round(v / m * 255)).join(',')})`;
}

function drawColors(svg, j) {
  const ns = 'http://www.w3.org/2000/svg';
  const add = (tag, attrs, text) => {
    const e = document.createElementNS(ns, tag);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    svg.appendChild(e);
    return e;
  };
  svg.innerHTML = '';
  add('circle', { cx: 0, cy: 0, r: 2, fill: '#888' });
  for (const b of j.blobs) {
    const [x, y] = plane(b);
    add('circle', { cx: x.toFixed(1), cy: y.toFixed(1), r: 1.6, fill: rgbOf(b), class: 'blob-dot', opacity: 0.8 });
  }
  if (!j.classes) return;
  for (const [a, b, key] of kPairs) {
    const [x1, y1] = plane(j.classes[a]), [x2, y2] = plane(j.classes[b]);
    add('line', { x1, y1, x2, y2, stroke: '#aaa', 'stroke-dasharray': '3 2', 'stroke-width': 0.6 });
    add('text', { x: (x1 + x2) / 2 + 2, y: (y1 + y2) / 2, fill: '#ccc', 'font-size': 7 },
        dv.fixed(j.separations[key], 0));
  }
  for (const [name, c] of Object.entries(j.classes)) {
    const [x, y] = plane(c);
    add('circle', { cx: x, cy: y, r: 5, fill: 'none', stroke: kClassStyle[name] || '#fff', 'stroke-width': 1.5,
                    class: 'class-ring', 'data-class': name });
    add('text', { x: x + 6, y: y - 6, fill: kClassStyle[name] || '#fff', 'font-size': 8 }, name);
  }
}

async function colorsPage() {
  const cams = (await dv.get('/api/cameras')).cameras;
  const select = document.getElementById('camera');
  for (const c of cams) select.add(new Option(`camera ${c.camera_id}`, c.camera_id));
  const svg = document.getElementById('chroma');
  dv.every(500, async () => {
    const j = await dv.get(`/api/cameras/${select.value}/colors`);
    drawColors(svg, j);
    document.getElementById('separations').textContent = j.separations
      ? `separations: yellow–blue ${dv.fixed(j.separations.yellow_blue, 0)}, green–pink ` +
        `${dv.fixed(j.separations.green_pink, 0)}, orange–field ${dv.fixed(j.separations.orange_field, 0)}` +
        ` · ${j.blobs.length} recent blobs`
      : 'waiting for the next frame…';
  });
}
