// Shared by every page of the console: the header (navigation and the
// operator's token), and the calls to the JSON API under /api/. The token is
// kept in this browser (localStorage); the URL serve prints carries it as
// #token=..., which never goes over the network.
'use strict';
const dv = {
  token() {
    const m = location.hash.match(/token=([^&]+)/);
    if (m) {
      localStorage.setItem('dvToken', decodeURIComponent(m[1]));
      history.replaceState(null, '', location.pathname + location.search);
    }
    return localStorage.getItem('dvToken') || '';
  },
  async get(path) {
    const r = await fetch(path, { cache: 'no-store' });
    if (!r.ok) throw new Error(path + ': HTTP ' + r.status);
    return r.json();
  },
  // A request that changes something; resolves to {status, body}.
  async send(method, path, body, type) {
    const r = await fetch(path, {
      method, body, cache: 'no-store',
      headers: { 'Authorization': 'Bearer ' + dv.token(), 'Content-Type': type || 'application/json' },
    });
    let parsed = null;
    try { parsed = await r.json(); } catch (e) { parsed = { error: 'HTTP ' + r.status }; }
    return { status: r.status, body: parsed };
  },
  header(active) {
    const pages = [['field.html', 'Field'], ['camera.html', 'Camera'], ['colors.html', 'Colors'],
                   ['calibration.html', 'Calibration'], ['status.html', 'Status'], ['settings.html', 'Settings']];
    const h = document.createElement('header');
    h.innerHTML = '<span class="brand">dotvision</span><nav>' +
      pages.map(([href, name]) => `<a href="${href}"${name === active ? ' class="active"' : ''}>${name}</a>`).join('') +
      '</nav><span class="token">token <input id="token" type="password" placeholder="needed for changes"></span>';
    document.body.prepend(h);
    const input = h.querySelector('#token');
    input.value = dv.token();
    input.addEventListener('change', () => localStorage.setItem('dvToken', input.value.trim()));
  },
  // Repeats `fn` every `ms` after each run ends (a slow answer never piles up).
  every(ms, fn) {
    const run = async () => {
      try { await fn(); } catch (e) { console.warn(e); }
      setTimeout(run, ms);
    };
    run();
  },
  fixed(v, digits) { return typeof v === 'number' && v >= 0 ? v.toFixed(digits) : '–'; },
  badgeText(c) {
    return `cam ${c.camera_id} · ${dv.fixed(c.fps_out, 1)} fps · ${dv.fixed(c.latency.total.p50_ms, 1)}/` +
           `${dv.fixed(c.latency.total.p99_ms, 1)} ms · ${c.health}`;
  },
};
