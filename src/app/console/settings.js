// The Settings page: robot heights and detector options as a form (sent as
// PATCH /api/config with the keys that changed, so the file keeps its
// comments), and the whole config text (PUT /api/config). Both go the way of
// a SIGHUP reload: a bad config is refused with its errors and the running
// one stays; "save" also writes the file. Changes need the operator's token.
'use strict';
const kNumberKeys = ['robot_heights.default', 'robot_heights.yellow', 'robot_heights.blue', 'detector.ball_radius'];
const kBoolKeys = ['detector.guessed_ids', 'detector.tracking'];
let shown = {};  // key -> value as loaded

function valueOf(values, key) {
  const [section, name] = key.split('.');
  return values[section][name];
}

async function load() {
  const c = await dv.get('/api/config?format=json');
  shown = {};
  for (const k of kNumberKeys) {
    const v = valueOf(c.values, k);
    document.getElementById(k).value = v === null ? '' : v;
    shown[k] = v;
  }
  for (const k of kBoolKeys) {
    document.getElementById(k).checked = valueOf(c.values, k);
    shown[k] = valueOf(c.values, k);
  }
  const teams = Object.entries(c.values.robot_heights.teams).map(([t, mm]) => `${t} ${mm}`).join(', ');
  document.getElementById('teams').textContent = teams ? `team table: ${teams} (edit it in the file below)` : '';
  document.getElementById('path').textContent = c.path;
  document.getElementById('text').value = c.text;
}

function report(id, r) {
  const box = document.getElementById(id);
  box.className = r.status === 200 ? 'notes' : 'error';
  box.textContent = r.status === 200
    ? (r.body.notes || []).join('\n') + (r.body.saved ? '\nsaved to the file' : '')
    : `refused (${r.status}): ${r.body.error || JSON.stringify(r.body)}`;
  box.dataset.status = r.status;
}

async function applyForm(save) {
  const edits = {};
  for (const k of kNumberKeys) {
    const text = document.getElementById(k).value.trim();
    const v = text === '' ? null : Number(text);
    if (v !== shown[k]) edits[k] = v;
  }
  for (const k of kBoolKeys) {
    const v = document.getElementById(k).checked;
    if (v !== shown[k]) edits[k] = v;
  }
  if (!Object.keys(edits).length && !save) return report('result', { status: 200, body: { notes: ['nothing changed'] } });
  const r = Object.keys(edits).length
    ? await dv.send('PATCH', '/api/config' + (save ? '?save=1' : ''), JSON.stringify(edits))
    : await dv.send('PUT', '/api/config?save=1', document.getElementById('text').value, 'application/yaml');
  report('result', r);
  if (r.status === 200) await load();
}

async function applyText(save) {
  const r = await dv.send('PUT', '/api/config' + (save ? '?save=1' : ''), document.getElementById('text').value,
                          'application/yaml');
  report('text-result', r);
  if (r.status === 200) await load();
}

async function settingsPage() {
  await load();
  document.getElementById('apply').onclick = () => applyForm(false);
  document.getElementById('apply-save').onclick = () => applyForm(true);
  document.getElementById('put').onclick = () => applyText(false);
  document.getElementById('put-save').onclick = () => applyText(true);
}
