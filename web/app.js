// web/app.js - the dashpot page: presets, the JSON editor, POST v1/simulate read as an NDJSON stream
// (fetch + ReadableStream reader) and plotted as it arrives, the well-posedness report of the meta line,
// problem+json errors shown at the member they point at, and the stability tab (POST v1/stability: the
// map as SVG, its counts as JSON). Every URL is relative, so the page works behind a path prefix. A 401
// (the daemon has a --token-file) asks for the bearer token, kept in sessionStorage for the tab. Picking a
// preset runs it (stopping a run in progress); Run (Ctrl+Enter) runs what the editor holds.
//
// For tests and curious people, #panel-simulate carries data-state (idle, running, done, error, stopped),
// data-samples (sample lines received), data-points (samples held for plotting), data-summary-samples and
// data-events, data-bands (stick intervals shaded) and data-run (runs started so far), data-budget (the
// output.max_samples the page asked for, empty when the request chose its own output) and data-every (the
// meta line's every; its warnings, if any, are listed in #warnings), data-stale ("true" while the plots are not the editor's request: after a refused
// request or a new preset), data-end ("contact" when the run stopped where its model is built to end, shown
// as a note, not a failure: web/right_hand.js); each canvas carries data-points (the points its last drawing
// went through).
// #panel-stability has data-state and data-run.
// #panel-sweep has data-state and data-run too (and web/sweep.js's own: the sweep tab streams POST v1/sweep and
// draws it as it arrives; a run clicked there opens here, in the simulate tab, as its own request).
//
// The sample budget: a request without an "output" member is sent with output.max_samples of about the
// plots' width in device pixels, so a 10^8-step run streams what the canvas can show, not 10^8 samples; the
// server picks every (docs/http.md), the page says the curve is decimated. An explicit output is sent as is.
// A network run (meta.model "network", docs/networks.md) is held and drawn by network.js instead, a
// right-hand friction run by right_hand.js (a network with contact elements adds web/contact.js's plots and
// impact markers), a linear complementarity system (meta.model "lcs") by lcs.js
// with the column names of the preset the request came from.

import { Table, Plot } from './plot.js';
import { Editor, pretty, locate } from './editor.js';
import { PRESETS } from './presets.js';
import { NetworkView } from './network.js';
import { runModes, renderModes } from './modes.js';
import { RightHandView, designedEnd } from './right_hand.js';
import { LcsView, lcsReport } from './lcs.js';
import { ContactPlots } from './contact.js';
import { QuakeView } from './quakes.js';
import { SweepView } from './sweep.js';

const $ = (id) => document.getElementById(id);
const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
const num = (v, d = 4) => (typeof v === 'number' ? (Number.isInteger(v) ? v.toLocaleString('en') : +v.toPrecision(d) + '') : '\u2014');
const MAX_POINTS = 2e6; // samples kept for plotting; a longer run is summarised, not drawn whole
const presetText = (p) => pretty(p.spec) + '\n';

const ui = {
  tab: 'simulate',
  text: { simulate: '', stability: '', modes: '', sweep: '' },
  preset: { simulate: '', stability: '', modes: '', sweep: '' },
  controller: null,
  mapUrl: null,
  runs: 0, // runs started, either tab (data-run)
  token: sessionStorage.getItem('dashpot-token') || '', // when the daemon wants one (--token-file)
};
const headers = (accept) => ({ 'Content-Type': 'application/json', Accept: accept,
  ...(ui.token ? { Authorization: 'Bearer ' + ui.token } : {}) });
const editor = new Editor($('editor'), () => run());
const network = new NetworkView(new ContactPlots()); // a network run (meta.model "network"), with contacts or not
const quakes = new QuakeView(); // a network run's quake lines (output.quakes): the Gutenberg-Richter plot
const rhView = new RightHandView(); // a run of a right-hand friction model (web/right_hand.js)
const RH_MODELS = ['piston-hinge', 'painleve-rod'];
const lcsView = new LcsView(); // a run of a linear complementarity system (web/lcs.js)

// ---- presets and tabs ----

function fillPresets() {
  const sel = $('preset');
  let group = null;
  for (const p of PRESETS) {
    if (!group || group.label !== p.group) {
      group = document.createElement('optgroup');
      group.label = p.group;
      sel.append(group);
    }
    group.append(new Option(p.label, p.id));
  }
  sel.prepend(new Option('(edited request)', ''));
  sel.options[0].disabled = true;
  sel.addEventListener('change', () => { loadPreset(sel.value); start(); }); // picking a preset runs it
}

// The preset menu names the preset only while the editor holds its request.
function syncPresetMenu() {
  const p = PRESETS.find((q) => q.id === ui.preset[ui.tab]);
  const same = p && editor.text.trim() === presetText(p).trim();
  $('preset').value = same ? p.id : '';
  if (p) $('preset-note').textContent = same ? p.note : `Edited from \u201c${p.label}\u201d; pick a preset to start again from one.`;
}

// Marks the plots as not showing the editor's request (why), or clears the mark (why = null).
function markStale(why) {
  const panel = $('panel-simulate');
  panel.dataset.stale = String(!!why);
  panel.classList.toggle('stale', !!why);
  $('stale-note').hidden = !why;
  if (why) $('stale-note').textContent = why;
}

function loadPreset(id) {
  stop();
  const p = PRESETS.find((q) => q.id === id) || PRESETS[0];
  ui.preset[p.kind] = p.id;
  ui.text[p.kind] = presetText(p);
  showTab(p.kind, true);
  history.replaceState(null, '', '#' + p.id);
  if (p.kind === 'simulate' && sim.meta) markStale(`Stale: these plots are from the previous run (${sim.label}); this preset is starting.`);
}

function showTab(tab, fromPreset = false) {
  if (!fromPreset) ui.text[ui.tab] = editor.text;
  if (ui.tab !== tab) stop();
  ui.tab = tab;
  for (const t of ['simulate', 'stability', 'modes', 'sweep']) {
    $('tab-' + t).setAttribute('aria-selected', String(t === tab));
    $('panel-' + t).hidden = t !== tab;
  }
  if (!ui.preset[tab]) { // the first visit of a tab starts with its first preset
    const p = PRESETS.find((q) => q.kind === tab);
    ui.preset[tab] = p.id;
    ui.text[tab] = presetText(p);
  }
  const p = PRESETS.find((q) => q.id === ui.preset[tab]);
  $('preset').value = p.id;
  $('preset-note').textContent = p.note;
  $('spec-label').textContent = { simulate: 'Request to v1/simulate (JSON)', stability: 'Request to v1/stability (JSON)',
    modes: 'Request to v1/modes and v1/response (JSON)', sweep: 'Sweep document to v1/sweep (JSON)' }[tab];
  editor.text = ui.text[tab];
  syncPresetMenu();
  showProblem(null);
  showWarnings(tab === 'simulate' && sim.meta ? sim.meta.warnings : null); // they belong to the simulate tab's run
  if (tab === 'simulate') drawAll();
}

// ---- problems: errors[].pointer marked in the editor, every message listed under it ----

// The meta line's warnings (docs/http.md: [{code, detail, pointer}], e.g. a step longer than a tenth of the
// shortest natural period at /solver/dt): a yellow note each under the run status, with a button to the
// line of the member it points at; none when the meta line has none (or null: clear them).
function showWarnings(warnings) {
  const box = $('warnings'), list = Array.isArray(warnings) ? warnings.filter((w) => w && typeof w === 'object') : [];
  box.hidden = list.length === 0;
  const text = editor.text;
  let where = null;
  try { where = locate(text); } catch { /* the member's line is then not offered */ }
  box.replaceChildren(...list.map((w) => {
    const li = document.createElement('li'), head = document.createElement('b');
    li.className = 'warning';
    li.dataset.code = w.code || '';
    head.textContent = '\u26a0 Warning' + (w.code ? ` (${w.code})` : '') + ': ';
    li.append(head, String(w.detail || 'no detail'));
    if (typeof w.pointer === 'string') {
      const code = document.createElement('code');
      code.textContent = w.pointer || '(the document)';
      li.append(' \u2014 at ', code);
      let p = w.pointer;
      while (where && !where.has(p) && p !== '') p = p.slice(0, p.lastIndexOf('/'));
      const loc = where && where.get(p);
      if (loc) {
        const [start, end] = [loc.key ? loc.key[0] : loc.value[0], loc.value[1]], b = document.createElement('button');
        b.type = 'button';
        b.className = 'link';
        b.textContent = `line ${text.slice(0, start).split('\n').length}`;
        b.addEventListener('click', () => editor.select({ start, end }));
        li.append(' (', b, ')');
      }
    }
    return li;
  }));
}

// The end a run was built to reach (web/right_hand.js: Painlevé's rod at the floor): a note, not a failure.
function showEnd(end, err) {
  $('end-note').hidden = !end;
  if (!end) return;
  $('end-title').textContent = end.title;
  $('end-text').textContent = end.text;
  $('end-detail').textContent = err && err.detail ? err.detail : '';
}

function showProblem(problem, prefix = '') {
  showEnd(null);
  const box = $('problem');
  box.hidden = !problem;
  $('token-form').hidden = !problem || problem.status !== 401;
  if (!problem) { editor.clearMarks(); return; }
  $('problem-title').textContent = prefix + (problem.status ? problem.status + ' ' : '') + (problem.title || 'Error') +
    (problem.detail ? ' \u2014 ' + problem.detail : '');
  const list = $('problem-list');
  list.replaceChildren();
  const marks = problem.errors ? editor.mark(problem.errors) : [];
  for (const mk of marks) {
    const li = document.createElement('li');
    li.innerHTML = `<button type="button" class="link">line ${mk.line}</button> <code>${esc(mk.pointer || '(document)')}</code> ${esc(mk.detail)}`;
    li.querySelector('button').addEventListener('click', () => editor.select(mk));
    list.append(li);
  }
  if (problem.errors_dropped) list.insertAdjacentHTML('beforeend', `<li>\u2026 and ${problem.errors_dropped} more</li>`);
}

async function problemOf(res) {
  try { return await res.json(); } catch { return { status: res.status, title: res.statusText }; }
}

// ---- simulation ----

let sim = newRun();

function newRun() {
  return { table: new Table(['t', 'x', 'v', 'Fs', 'Fd', 'Fc']), net: null, rh: null, lcs: null, events: [], stick: [], stickStart: null,
    meta: null, summary: null, error: null, end: null, samples: 0, lastT: 0, tEnd: 1, vb: 0, started: performance.now(), budget: 0,
    label: '', preset: null, spec: null };
}
// The run held by a view of its own (network, right-hand, LCS), or null for the one-mass plots.
const viewRun = () => sim.net || sim.rh || sim.lcs;

const stickBands = () => (sim.stickStart === null ? sim.stick : [...sim.stick, [sim.stickStart, sim.lastT]]);
const timeAxis = { col: 't', label: 't', monotone: true, range: () => [0, sim.tEnd] };
const plots = [
  new Plot($('plot-xv'), { x: timeAxis, y: { label: 'x, v' }, bands: stickBands,
    series: [{ col: 'x', color: '--c-x' }, { col: 'v', color: '--c-v' }],
    markers: () => sim.events.map((e) => ({ x: e.t, y: e.x, kind: e.kind })) }),
  new Plot($('plot-forces'), { x: timeAxis, y: { label: 'force' }, bands: stickBands,
    series: [{ col: 'Fs', color: '--c-Fs' }, { col: 'Fd', color: '--c-Fd' }, { col: 'Fc', color: '--c-Fc', dash: [6, 4] }] }),
  new Plot($('plot-phase'), { x: { col: 'x', label: 'x' }, y: { label: 'v' }, series: [{ col: 'v', color: '--c-phase' }],
    markers: () => sim.events.map((e) => ({ x: e.x, y: e.v, kind: e.kind })) }),
  new Plot($('plot-law'), { x: { col: 'v', label: 'v' }, y: { label: 'Fd' }, series: [{ col: 'Fd', color: '--c-Fd' }] }),
  new Plot($('plot-spring'), { x: { col: 'x', label: 'x' }, y: { label: 'Fs' }, series: [{ col: 'Fs', color: '--c-Fs' }] }),
];

function drawAll() {
  network.show(!!sim.net);
  rhView.show(!!sim.rh);
  lcsView.show(!!sim.lcs);
  if (sim.rh) { $('plots-one').hidden = true; rhView.draw(sim.rh); return; }
  if (sim.lcs) { $('plots-one').hidden = true; lcsView.draw(sim.lcs); return; }
  if (sim.net) { network.draw(sim.net); quakes.draw(); return; }
  for (const p of plots) { p.setTable(sim.table); p.draw(); }
  // the marker legend names the kinds this run's events have (stick/slip, or an elastoplastic yield/unload)
  const kinds = new Set(sim.events.map((e) => e.kind));
  for (const e of $('plots-one').querySelectorAll('.legend [data-kind]')) e.hidden = !kinds.has(e.dataset.kind);
}

let frame = 0;
function scheduleDraw() {
  if (!frame) frame = requestAnimationFrame(() => { frame = 0; drawAll(); showProgress(); });
}

function setSimState(state) {
  const d = $('panel-simulate').dataset;
  d.state = state;
  d.samples = sim.samples;
  d.points = (viewRun() || sim).table.n;
  d.events = sim.events.length;
  d.summarySamples = sim.summary ? sim.summary.samples : '';
  d.bands = stickBands().length;
  d.run = ui.runs;
  d.budget = sim.budget || '';
  d.every = sim.meta ? sim.meta.every : '';
  d.end = sim.end ? sim.end.kind : '';
}

// About the plots' width in device pixels: more samples than that cannot be told apart on the canvas.
function sampleBudget() {
  const w = Math.max(...plots.map((p) => p.canvas.clientWidth)) * (window.devicePixelRatio || 1);
  return Math.min(10000, Math.max(200, Math.round(w)));
}

// The request as sent: with the sample budget when it has no "output" member of its own (see the top).
function withBudget(text) {
  let spec;
  try { spec = JSON.parse(text); } catch { return { body: text, budget: 0 }; } // the daemon says where
  if (!spec || typeof spec !== 'object' || Array.isArray(spec) || 'output' in spec || Object.keys(spec).length === 0)
    return { body: text, budget: 0 };
  const budget = sampleBudget();
  return { body: text.replace(/^\s*\{/, (open) => `${open}"output": {"max_samples": ${budget}}, `), budget };
}

function onRecord(o) {
  switch (o.type) {
    case 'sample':
      sim.samples++;
      sim.lastT = o.t;
      if (sim.net) { sim.net.push(o); break; }
      if (sim.rh) { sim.rh.push(o); break; }
      if (sim.lcs) { sim.lcs.push(o); break; }
      if (sim.table.n < MAX_POINTS) sim.table.push(o);
      if (o.phase === 'stick' && sim.stickStart === null) sim.stickStart = o.t;
      if (o.phase === 'slip' && sim.stickStart !== null) { sim.stick.push([sim.stickStart, o.t]); sim.stickStart = null; }
      break;
    case 'event': // located transitions: the shading starts and ends at the event, not at the next sample
      sim.events.push(o);
      if (sim.rh) { sim.rh.event(o); break; }
      if (sim.net && sim.net.event) { sim.net.event(o); break; } // impacts (web/contact.js)
      if (o.kind === 'stick' && sim.stickStart === null) sim.stickStart = o.t;
      if (o.kind === 'slip' && sim.stickStart !== null) { sim.stick.push([sim.stickStart, o.t]); sim.stickStart = null; }
      break;
    case 'quake': quakes.push(o); break;
    case 'meta':
      quakes.reset();
      sim.meta = o;
      sim.tEnd = o.t_end;
      if (o.model === 'network') sim.net = network.start(o, sim.spec);
      if (RH_MODELS.includes(o.model)) sim.rh = rhView.start(o);
      if (o.model === 'lcs') sim.lcs = lcsView.start(o, sim.preset && sim.preset.columns);
      renderWellposedness(o.wellposedness, o);
      showWarnings(o.warnings);
      break;
    case 'summary': sim.summary = o; break;
    case 'error': sim.error = o; if (sim.rh) sim.rh.stop(o, sim.lastT); break;
  }
}

async function runSimulation() {
  const ctl = new AbortController();
  ui.controller = ctl;
  const mine = ++ui.runs;
  showProblem(null);
  showWarnings(null);
  setSimState('running');
  setRunning(true);
  $('status').textContent = 'sending\u2026';
  const started = performance.now();
  const label = $('preset').value ? $('preset').selectedOptions[0].textContent : 'an edited request';
  const { body, budget } = withBudget(editor.text);
  let state = 'error';
  try {
    const res = await fetch('v1/simulate', { method: 'POST', body, signal: ctl.signal,
      headers: headers('application/x-ndjson') });
    if (!res.ok) { // no run: the last one stays on screen, marked stale; the problem goes next to the editor
      showProblem(await problemOf(res));
      if (sim.meta) markStale(`Stale: the plots are from the previous run (${sim.label}), not from this request (${res.status}).`);
      return;
    }
    sim = newRun();
    sim.started = started;
    sim.budget = budget;
    sim.label = label;
    sim.preset = PRESETS.find((q) => q.id === ui.preset.simulate) || null; // names an LCS run's columns
    try { sim.spec = JSON.parse(body); } catch { sim.spec = null; } // says which network elements are contacts
    markStale(null);
    renderStats();
    drawAll();
    $('wp-body').innerHTML = '<span class="muted">waiting for the meta line\u2026</span>';
    const reader = res.body.getReader(), dec = new TextDecoder();
    let buf = '';
    for (;;) {
      const { value, done } = await reader.read();
      if (done) break;
      buf += dec.decode(value, { stream: true });
      let at = 0, nl;
      while ((nl = buf.indexOf('\n', at)) >= 0) {
        if (nl > at) onRecord(JSON.parse(buf.slice(at, nl)));
        at = nl + 1;
      }
      buf = buf.slice(at);
      scheduleDraw();
    }
    buf += dec.decode();
    if (buf.trim()) onRecord(JSON.parse(buf));
    sim.end = sim.error && sim.rh ? designedEnd(sim.meta, sim.error) : null;
    if (sim.end) showEnd(sim.end, sim.error);
    else if (sim.error) showProblem(sim.error, 'The run stopped: ');
    else if (!sim.summary) showProblem({ title: 'The stream ended without its summary line' });
    state = (sim.summary && !sim.error) || sim.end ? 'done' : 'error';
  } catch (e) {
    if (e.name === 'AbortError') state = 'stopped';
    else showProblem({ title: 'Cannot reach the daemon', detail: String(e.message || e) });
  } finally {
    if (ui.controller === ctl) {
      ui.controller = null;
      setRunning(false);
    }
    if (mine === ui.runs) { // not when a newer run (a preset picked meanwhile) has taken over the page
      drawAll();
      renderStats(state);
      setSimState(state);
    }
  }
}

function showProgress() {
  if (!ui.controller || ui.tab !== 'simulate') return;
  $('progress').value = sim.tEnd > 0 ? Math.min(1, sim.lastT / sim.tEnd) : 0;
  $('status').textContent = `streaming\u2026 t = ${num(sim.lastT, 3)} of ${num(sim.tEnd)}`;
  renderStats();
}

function renderStats(state) {
  const m = sim.meta, s = sim.summary;
  const chip = (k, v) => `<span class="chip"><b>${esc(k)}</b> ${esc(v)}</span>`;
  let h = '';
  if (m) {
    h += chip('solver', m.solver + (m.variant ? ' (' + m.variant + ')' : m.scheme ? ' (' + m.scheme + ')' : ''));
    if (m.theta !== undefined) h += chip('\u03b8', num(m.theta));
    if (m.scheme) h += chip(m.scheme === 'PI' ? 'k' : 'n', num(m.scheme === 'PI' ? m.k : m.n)) + chip('stepper', m.stepper);
    h += chip('dt', num(m.dt)) + chip('T', num(m.t_end));
    if (m.every > 1) h += `<span class="chip warn" id="decimated" title="output.every = ${m.every}">decimated: 1 sample per ${num(m.every)} steps` +
      (sim.budget ? ` (at most ${num(sim.budget)}, about the plot width; set "output" in the request to choose)` : '') + '</span>';
    if (m.branch) h += chip('branch', m.branch);
    if (m.model === 'network') h += chip('nodes', num(m.nodes)) + chip('elements', num(m.elements));
    if (m.model === 'lcs') h += chip('states', num(m.states)) + chip('components', num(m.components));
    const wp = m.wellposedness;
    if (wp) for (const k of ['existence', 'uniqueness'])
      h += `<span class="chip ${wp[k].guaranteed ? 'ok' : 'no'}" title="${esc(wp[k].theorem || wp[k].reason)}"><b>${k}</b> ${wp[k].guaranteed ? '\u2713' : '\u2717 not'} guaranteed</span>`;
  }
  h += chip('samples', num(sim.samples)) + chip('events', num(sim.events.length));
  if (s) {
    if (!sim.lcs) h += chip('stick time', num(s.stick_time));
    if (!viewRun()) h += chip('final x', num(s.final.x, 6));
    if (sim.samples > (viewRun() || sim).table.n) h += `<span class="chip warn">plotted the first ${num(sim.table.n)} samples</span>`;
  }
  $('stats').innerHTML = h;
  if (state === 'done') {
    const secs = (performance.now() - sim.started) / 1000;
    const ev = sim.events.length;
    $('status').textContent = `${num(sim.samples)} samples \u00b7 ${ev} event${ev === 1 ? '' : 's'} \u00b7 ${secs.toFixed(2)} s` +
      (sim.end && sim.rh && sim.rh.stopAt !== null ? ` \u00b7 ended at contact, t = ${num(sim.rh.stopAt)}` : '');
  } else if (state === 'stopped') $('status').textContent = 'stopped';
  else if (state === 'error') $('status').textContent = 'failed';
}

function renderWellposedness(wp, meta) {
  const body = $('wp-body');
  if (!wp && meta.model === 'lcs') { body.innerHTML = lcsReport(meta); return; }
  if (!wp) { body.textContent = 'The meta line has no well-posedness report.'; return; }
  const verdict = (name, r) => `<div class="verdict ${r.guaranteed ? 'ok' : 'no'}">
      <span class="badge">${r.guaranteed ? '\u2713' : '\u2717'} ${name} ${r.guaranteed ? 'guaranteed' : 'not guaranteed'}</span>
      <span>${esc(r.guaranteed ? r.theorem : r.reason)}</span></div>`;
  let h = `<p class="muted">Framework ${esc(wp.framework)}: which theorems of the sources apply to this model.</p>` +
    verdict('Existence', wp.existence) + verdict('Uniqueness', wp.uniqueness);
  if (wp.counterexample) {
    h += `<p class="counter"><b>Counterexample.</b> ${esc(wp.counterexample)}.`;
    if (wp.branches) h += ' Branches: ' + wp.branches.map((b) => `<span class="chip${b === meta.branch ? ' on' : ''}">${esc(b)}</span>`).join(' ') +
      ` \u2014 this run follows <b>${esc(meta.branch)}</b> (solver.branch).`;
    h += '</p>';
  }
  h += '<ul class="checks">' + wp.checks.map((c) => `<li class="${c.holds ? 'ok' : 'no'}"><span class="tick">${c.holds ? '\u2713' : '\u2717'}</span>
      <span>${esc(c.hypothesis)}:</span> <span class="muted">${esc(c.detail)}</span></li>`).join('') + '</ul>';
  body.innerHTML = h;
}

// ---- stability ----

// A run of a tab whose answer is computed whole or streamed into its panel (stability, modes, sweep): the
// panel marked running, `work(ctl, text)` given the abort controller and the editor's text; it returns 'done'
// when it succeeded (on a problem it shows it and returns nothing). The panel then ends 'done', 'stopped'
// (aborted) or 'error', and the status line says so unless done.
async function panelRun(panelId, busy, work) {
  const ctl = new AbortController();
  ui.controller = ctl;
  const panel = $(panelId);
  const text = editor.text;
  const mine = ++ui.runs;
  panel.dataset.run = mine;
  showProblem(null);
  panel.dataset.state = 'running';
  setRunning(true);
  $('status').textContent = busy;
  let state = 'error';
  try {
    state = (await work(ctl, text)) || 'error';
  } catch (e) {
    if (e.name === 'AbortError') state = 'stopped';
    else showProblem({ title: 'Cannot reach the daemon', detail: String(e.message || e) });
  } finally {
    if (ui.controller === ctl) { ui.controller = null; setRunning(false); }
    if (mine === ui.runs) {
      panel.dataset.state = state;
      if (state !== 'done') $('status').textContent = state === 'stopped' ? 'stopped' : 'failed';
    }
  }
}

function runStability() {
  let map = false;
  try { map = !!JSON.parse(editor.text).map; } catch { /* the daemon says where */ }
  return panelRun('panel-stability', map ? 'computing the map\u2026' : 'analysing\u2026', async (ctl, text) => {
    const post = (accept) => fetch('v1/stability', { method: 'POST', body: text, signal: ctl.signal,
      headers: headers(accept) });
    const t0 = performance.now();
    const [jr, sr] = await Promise.all([post('application/json'), map ? post('image/svg+xml') : null]);
    if (!jr.ok) { showProblem(await problemOf(jr)); return; }
    const doc = await jr.json();
    const img = $('stab-img');
    if (ui.mapUrl) URL.revokeObjectURL(ui.mapUrl);
    ui.mapUrl = null;
    if (sr && sr.ok) {
      ui.mapUrl = URL.createObjectURL(await sr.blob());
      img.src = ui.mapUrl;
      await img.decode();
    }
    img.hidden = !ui.mapUrl;
    $('stab-empty').hidden = true;
    renderStability(doc);
    $('status').textContent = `done in ${((performance.now() - t0) / 1000).toFixed(2)} s`;
    return 'done';
  });
}

const VERDICT_CLASS = { 'asymptotically stable': 'ok', unstable: 'no', 'marginally stable': 'mid', 'near boundary': 'mid' };

function renderStability(d) {
  const chip = (k, v, cls = '') => `<span class="chip ${cls}"><b>${esc(k)}</b> ${esc(v)}</span>`;
  let info = '', more = '';
  if (d.map) {
    const m = d.map, c = m.counts, n = Object.values(c).reduce((a, b) => a + b, 0);
    info += chip(m.x.param, `${num(m.x.from)} \u2026 ${num(m.x.to)} (${m.x.steps})`) +
      chip(m.y.param, `${num(m.y.from)} \u2026 ${num(m.y.to)} (${m.y.steps})`);
    for (const [k, label] of Object.entries(m.legend)) if (c[k]) info += chip(label, `${num(c[k])} (${(100 * c[k] / n).toFixed(1)}%)`, VERDICT_CLASS[label] || '');
    const cf = m.closed_form;
    if (cf) more = `<p>Thesis model ${esc(cf.name)}: stable iff ${esc(cf.condition)} <code>${esc(cf.expression)}</code> \u2014 the black line on the map.</p>`;
    $('stab-img').alt = `stability map over ${m.x.param} and ${m.y.param}`;
  } else {
    info += chip('verdict', d.verdict, VERDICT_CLASS[d.verdict] || '') + chip('spectral abscissa', num(d.spectral_abscissa, 6));
    more = `<p><b>p(z)</b> coefficients (highest power first): <code>${esc(d.polynomial.coefficients.map((x) => num(x, 6)).join(', '))}</code></p>
      <table class="roots"><thead><tr><th>root</th><th>Re z</th><th>Im z</th><th>error bound</th></tr></thead><tbody>` +
      d.roots.map((r, i) => `<tr><td>${i + 1}</td><td>${num(r.re, 8)}</td><td>${num(r.im, 8)}</td><td>${num(r.error, 2)}</td></tr>`).join('') +
      `</tbody></table><p>Hurwitz minors: <code>${esc((d.hurwitz_minors || []).map((x) => num(x, 6)).join(', '))}</code></p>`;
    if (d.model) {
      const lhs = d.model.expression.replace(/\s*>\s*0$/, ''); // "value" is the left side of "... > 0"
      more += `<p id="stab-model">Thesis model ${esc(d.model.name)}, stable iff ${esc(d.model.condition)} <code>${esc(d.model.expression)}</code>; here ` +
        `<code>${esc(lhs)}</code> = ${num(d.model.value, 6)}: ${esc(d.model.verdict ?? 'does not apply')}</p>`;
    }
  }
  $('stab-info').innerHTML = info;
  $('stab-analysis').innerHTML = more;
}

// ---- modes and frequency response (web/modes.js) ----

function runModesTab() {
  return panelRun('panel-modes', 'analysing\u2026', async (ctl, text) => {
    const post = (route) => fetch(route, { method: 'POST', body: text, signal: ctl.signal, headers: headers('application/json') });
    const t0 = performance.now();
    const { mr, rr } = await runModes(post, text);
    if (!mr.ok) { showProblem(await problemOf(mr)); return; }
    if (rr && !rr.ok) { showProblem(await problemOf(rr)); return; }
    renderModes(await mr.json(), rr ? await rr.json() : null);
    $('status').textContent = `done in ${((performance.now() - t0) / 1000).toFixed(2)} s`;
    return 'done';
  });
}

// ---- sweeps (web/sweep.js): POST v1/sweep streamed, drawn as its lines arrive ----

// A run of the sweep opened in the trajectory view: its simulate document in the simulate tab's editor, run.
function openTrajectory(doc, label) {
  stop();
  if (!ui.preset.simulate) ui.preset.simulate = PRESETS.find((q) => q.kind === 'simulate').id; // else showTab loads it
  ui.text.simulate = pretty(doc) + '\n';
  showTab('simulate');
  start();
  $('preset-note').textContent = label; // until the next run or preset: where this request came from
}
const sweepView = new SweepView(openTrajectory);

function runSweepTab() {
  return panelRun('panel-sweep', 'sweeping\u2026', async (ctl, text) => {
    const t0 = performance.now();
    const res = await fetch('v1/sweep', { method: 'POST', body: text, signal: ctl.signal, headers: headers('application/x-ndjson') });
    if (!res.ok) { showProblem(await problemOf(res)); return; }
    const p = PRESETS.find((q) => q.id === ui.preset.sweep && presetText(q).trim() === text.trim());
    sweepView.start(text, p ? p.view : null, p ? p.reference : null);
    const reader = res.body.getReader(), dec = new TextDecoder();
    let buf = '', error = null, summary = null;
    const line = (l) => { const o = JSON.parse(l); if (o.type === 'error') error = o; if (o.type === 'summary') summary = o; sweepView.line(o); };
    for (;;) {
      const { value, done } = await reader.read();
      if (done) break;
      buf += dec.decode(value, { stream: true });
      let at = 0, nl;
      while ((nl = buf.indexOf('\n', at)) >= 0) { if (nl > at) line(buf.slice(at, nl)); at = nl + 1; }
      buf = buf.slice(at);
      $('status').textContent = `sweeping\u2026 ${sweepView.s.runs.size} of ${sweepView.s.meta ? sweepView.s.meta.selected : '?'} runs`;
    }
    buf += dec.decode();
    if (buf.trim()) line(buf);
    sweepView.draw();
    if (error) showProblem(error, 'The sweep stopped: ');
    else if (!summary) showProblem({ title: 'The stream ended without its summary line' });
    else {
      $('status').textContent = `${summary.completed} runs` + (summary.failed ? `, ${summary.failed} failed` : '') +
        ` \u00b7 ${((performance.now() - t0) / 1000).toFixed(2)} s`;
      return 'done';
    }
  });
}

// ---- run / stop ----

function setRunning(on) {
  const b = $('run');
  b.textContent = on ? 'Stop' : 'Run';
  b.classList.toggle('stop', on);
  $('progress').hidden = !on || (ui.tab !== 'simulate' && ui.tab !== 'sweep');
  if (!on) $('progress').value = 0;
}

function stop() {
  if (ui.controller) ui.controller.abort();
}

// The Run button and Ctrl+Enter: stops a run in progress, else starts one.
function run() {
  if (ui.controller) { stop(); return; }
  start();
}

// Starts the editor's request on the open tab, stopping a run in progress (its ending then leaves the page
// to this one: the runs' `mine === ui.runs` above).
function start() {
  stop();
  ui.controller = null;
  ui.text[ui.tab] = editor.text;
  syncPresetMenu();
  if (ui.tab === 'simulate') runSimulation(); else if (ui.tab === 'modes') runModesTab();
  else if (ui.tab === 'sweep') runSweepTab(); else runStability();
}

$('run').addEventListener('click', run);
$('token-form').addEventListener('submit', (e) => {
  e.preventDefault();
  ui.token = $('token').value.trim();
  sessionStorage.setItem('dashpot-token', ui.token);
  run();
});
$('format').addEventListener('click', () => {
  try { editor.text = pretty(JSON.parse(editor.text)) + '\n'; } catch {
    showProblem({ title: 'Not valid JSON', detail: 'fix it, or Run to see where the daemon stops reading' });
  }
});
for (const t of ['simulate', 'stability', 'modes', 'sweep']) $('tab-' + t).addEventListener('click', () => { if (ui.tab !== t) showTab(t); });
fillPresets();
loadPreset(location.hash.slice(1) || 'thesis-5-gamma');
start();
