// web/sweep.js - the sweep tab: POST v1/sweep read as NDJSON (docs/sweep.md: a meta line, one line per run
// as it completes, a summary) and drawn as the lines arrive. Studies of friction oscillators publish their
// results as pictures over a parameter: the response curve (Den Hartog 1931's amplitude against the forcing
// frequency), the bifurcation diagram (Poincaré points against the belt speed), a map of a feature over two
// parameters. Here:
// - the response curve: a feature (picked in #sweep-feature) against the first parameter, one dot per run;
//   with two parameters one curve per value of the second, and the map of the feature coloured over the grid;
// - the bifurcation diagram: each run's section points' x against the first parameter;
// - a run whose feature is null is an open grey dot on the bottom edge (the line's reason as its tooltip), a
//   run that failed a red cross there and a line in #sweep-failed: none is dropped silently;
// - a click on a run (its dot, its column of the diagram, its cell) opens it: the sweep's base document with
//   the run's values put at the pointers (each number as the line gives it, so the same double) goes to the
//   simulate tab's trajectory view (opener, given by web/app.js), with 10 001 samples unless it sets output.
// Drawn as SVG like web/modes.js (presentation attributes, never style: the CSP refuses inline styles).
//
// For tests: #panel-sweep carries data-runs (the meta line's selected runs), data-received (run lines read),
// data-failed, data-nulls (runs whose picked feature is null) and data-feature; each <svg> data-points (dots,
// section points or coloured cells drawn); each dot is a <circle class="pt"> with data-index, data-x (the
// parameter) and data-y (the feature) as the line has them; failed runs are <path class="failed">, null ones
// <circle class="null">.

import { niceStep, tickLabel } from './plot.js';

const NS = 'http://www.w3.org/2000/svg';
const INK = '#1d2433', SOFT = '#5b6475', GRID = '#eceef2', FRAME = '#b9c0cc', FAIL = '#b42318', NULLC = '#8b93a1';
const REF = '#bf8700';
// viridis, sampled at 7 stops (low: dark violet, high: yellow)
const VIRIDIS = [[68, 1, 84], [68, 57, 131], [49, 104, 142], [33, 145, 140], [53, 183, 121], [144, 215, 67], [253, 231, 37]];
const $ = (id) => document.getElementById(id);
const fmt = (v) => (typeof v === 'number' ? String(+v.toPrecision(5)) : '\u2014');

export const FEATURES = ['amplitude', 'x_max', 'x_min', 'v_max', 'v_min', 'period', 'stick_fraction'];

// A parameter's name for axes and labels: the pointer's last member (Greek where the documents spell it out).
const GREEK = { omega: '\u03c9', phi0: '\u03c6\u2080', phi1: '\u03c6\u2081', theta: '\u03b8', mass: 'm', amplitude: 'P',
  belt_velocity: 'belt speed', k: 'k', c: 'c' };
export function paramName(pointer) {
  const last = pointer.split('/').pop().replace(/~1/g, '/').replace(/~0/g, '~');
  return GREEK[last] || last;
}

// The base with each value put at its pointer (RFC 6901; a missing member of an existing object is added,
// as the sweep does): the run's own simulate document.
export function putValues(base, pointers, values) {
  const doc = structuredClone(base);
  pointers.forEach((p, j) => {
    const keys = p.split('/').slice(1).map((k) => k.replace(/~1/g, '/').replace(/~0/g, '~'));
    let o = doc;
    for (const k of keys.slice(0, -1)) o = o[Array.isArray(o) ? +k : k];
    const last = keys[keys.length - 1];
    o[Array.isArray(o) ? +last : last] = values[j];
  });
  return doc;
}

function el(tag, attrs = {}, text) {
  const e = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

function chart(svg, right = 14) {
  const w = Math.max(160, svg.clientWidth), h = Math.max(140, svg.clientHeight);
  svg.replaceChildren();
  svg.setAttribute('viewBox', `0 0 ${w} ${h}`);
  svg.setAttribute('font-family', 'system-ui, sans-serif');
  return { svg, w, h, l: 62, t: 10, pw: w - 62 - right, ph: h - 10 - 42 };
}

// A scale over [lo, hi] (log10 when log): nice ends, ticks with labels, and the map to pixels.
function scale(lo, hi, log, from, length, flip) {
  if (log) { lo = Math.log10(lo); hi = Math.log10(hi); }
  if (!Number.isFinite(lo) || !Number.isFinite(hi)) [lo, hi] = [0, 1];
  if (hi - lo < 1e-12 * Math.max(1, Math.abs(lo))) { const d = Math.abs(lo) * 0.1 || 1; lo -= d; hi += d; }
  const pad = 0.04 * (hi - lo);
  lo -= pad;
  hi += pad;
  const count = Math.max(2, Math.round(length / (flip ? 48 : 90)));
  const at = (v) => { const u = ((log ? Math.log10(v) : v) - lo) / (hi - lo); return flip ? from + length * (1 - u) : from + length * u; };
  const ticks = [];
  if (log) {
    const step = Math.max(1, Math.round(niceStep(lo, hi, count)));
    const dense = hi - lo < 2; // few decades: 2 and 5 times them too
    for (let k = Math.floor(lo); k <= Math.ceil(hi); k += dense ? 1 : step)
      for (const m of dense ? [1, 2, 5] : [1]) {
        const e = k + Math.log10(m);
        if (e >= lo && e <= hi) ticks.push({ at: at(10 ** e), label: String(+(10 ** e).toPrecision(3)) });
      }
  } else {
    const s = niceStep(lo, hi, count);
    for (let v = Math.ceil(lo / s - 1e-9) * s; v <= hi + s * 1e-9; v += s) {
      const x = Math.abs(v) < s * 1e-9 ? 0 : v;
      ticks.push({ at: at(x), label: tickLabel(x, s).replace(/-/g, '\u2212') });
    }
  }
  return { at, ticks };
}

function axis(c, which, ticks, title) {
  const g = el('g', { class: `axis ${which}`, 'font-size': 12, fill: SOFT });
  for (const { at, label } of ticks) {
    const p = Math.round(at) + 0.5;
    if (which === 'x') {
      g.append(el('line', { x1: p, x2: p, y1: c.t, y2: c.t + c.ph, stroke: GRID }),
        el('text', { class: 'tick', x: p, y: c.t + c.ph + 17, 'text-anchor': 'middle' }, label));
    } else {
      g.append(el('line', { x1: c.l, x2: c.l + c.pw, y1: p, y2: p, stroke: GRID }),
        el('text', { class: 'tick', x: c.l - 7, y: p + 4, 'text-anchor': 'end' }, label));
    }
  }
  g.append(which === 'x'
    ? el('text', { class: 'title', x: c.l + c.pw / 2, y: c.h - 5, 'text-anchor': 'middle', 'font-style': 'italic', 'font-size': 13, fill: INK }, title)
    : el('text', { class: 'title', transform: `translate(15 ${c.t + c.ph / 2}) rotate(-90)`, 'text-anchor': 'middle',
      'font-style': 'italic', 'font-size': 13, fill: INK }, title));
  c.svg.append(g);
}

const frame = (c) => el('rect', { class: 'frame', x: c.l + 0.5, y: c.t + 0.5, width: c.pw - 1, height: c.ph - 1, fill: 'none', stroke: FRAME });
const cross = (x, y, cls, index) => el('path', { class: cls, 'data-index': index, d: `M${x - 4},${y - 4}L${x + 4},${y + 4}M${x - 4},${y + 4}L${x + 4},${y - 4}`,
  stroke: FAIL, 'stroke-width': 2 });

// The colour of the curve of the second parameter's value i of n: the map's scale (the yellow end left out, too
// light on white), so a curve and its row of cells read alike.
const family = (i, n) => viridis(n > 1 ? 0.85 * i / (n - 1) : 0);

function viridis(u) {
  const x = Math.min(1, Math.max(0, u)) * (VIRIDIS.length - 1), i = Math.min(VIRIDIS.length - 2, Math.floor(x)), f = x - i;
  const [a, b] = [VIRIDIS[i], VIRIDIS[i + 1]];
  return `rgb(${a.map((v, k) => Math.round(v + f * (b[k] - v))).join(',')})`;
}

export class SweepView {
  // opener(doc, label): shows a run's simulate document in the trajectory view.
  constructor(opener) {
    this.opener = opener;
    this.s = null;
    this.frame = 0;
    this.hot = null; // the hovered run's index
    $('sweep-feature').addEventListener('change', () => this.draw());
    $('sweep-log').addEventListener('change', () => this.draw());
    const resized = new ResizeObserver(() => this.schedule());
    for (const id of ['sweep-curve', 'sweep-bif', 'sweep-map']) {
      const svg = $(id);
      resized.observe(svg);
      svg.addEventListener('mousemove', (e) => this.hover(svg, e));
      svg.addEventListener('mouseleave', () => { this.hot = null; this.info(); });
      svg.addEventListener('click', (e) => { const i = this.nearest(svg, e); if (i !== null) this.open(i); });
    }
  }

  // A new sweep of the document text (its base kept for the runs' trajectories); view: the preset's
  // {feature, log} or null; reference: a closed form of the first parameter to draw dashed, or null.
  start(text, view, reference) {
    let doc = null;
    try { doc = JSON.parse(text); } catch { /* the daemon says where */ }
    this.s = { doc, meta: null, runs: new Map(), failed: [], summary: null, error: null, reference: reference || null };
    featureOptions(FEATURES);
    if (view && view.feature) $('sweep-feature').value = view.feature;
    if (view) $('sweep-log').checked = !!view.log;
    this.draw();
  }

  line(o) {
    const s = this.s;
    if (o.type === 'meta') s.meta = o;
    else if (o.type === 'run') {
      s.runs.set(o.index, o);
      if (o.status) s.failed.push(o);
    } else if (o.type === 'summary') s.summary = o;
    else if (o.type === 'error') s.error = o;
    this.schedule();
  }

  schedule() {
    if (!this.frame) this.frame = requestAnimationFrame(() => { this.frame = 0; this.draw(); });
  }

  axes() { return this.s && this.s.meta ? this.s.meta.axes : []; }

  draw() {
    const s = this.s, panel = $('panel-sweep');
    if (!s) return;
    const axes = this.axes(), two = axes.length === 2;
    const feats = s.meta ? s.meta.record.features : FEATURES;
    featureOptions(feats);
    const f = $('sweep-feature').value;
    $('sweep-map-figure').hidden = !two;
    const sec = !s.meta || !!s.meta.record.section; // no section: no diagram, the curve takes the row
    $('sweep-bif').closest('figure').hidden = !sec;
    $('sweep-curve').closest('figure').classList.toggle('wide', !sec);
    this.drawCurve(f, axes);
    this.drawBifurcation(axes);
    if (two) this.drawMap(f, axes);
    this.list();
    this.info();
    const runs = [...s.runs.values()];
    panel.dataset.runs = s.meta ? s.meta.selected : '';
    panel.dataset.received = runs.length;
    panel.dataset.failed = s.failed.length;
    panel.dataset.nulls = runs.filter((r) => !r.status && r.features && r.features[f] === null).length;
    panel.dataset.feature = f;
    if (s.meta) $('progress').value = s.meta.selected ? runs.length / s.meta.selected : 1;
  }

  // The feature against the first parameter; one curve per value of the second.
  drawCurve(f, axes) {
    const svg = $('sweep-curve'), s = this.s;
    const c = chart(svg), runs = [...s.runs.values()];
    const ok = runs.filter((r) => !r.status && typeof r.features[f] === 'number');
    const xs = axes.length ? axes[0].values : [0, 1];
    const logX = this.logAxis(0), ys = ok.map((r) => r.features[f]);
    const logY = $('sweep-log').checked && ys.length > 0 && ys.every((y) => y > 0);
    $('sweep-log').disabled = ys.some((y) => !(y > 0));
    const X = scale(Math.min(...xs), Math.max(...xs), logX, c.l, c.pw, false);
    const Y = scale(ys.length ? Math.min(...ys) : 0, ys.length ? Math.max(...ys) : 1, logY, c.t, c.ph, true);
    const name = axes.length ? paramName(axes[0].pointer) : 'parameter';
    axis(c, 'x', X.ticks, axes.length ? `${name}  (${axes[0].pointer})` : name);
    axis(c, 'y', Y.ticks, f + (logY ? ' (log)' : ''));
    if (s.reference && axes.length) { // the closed form, where it is defined
      let d = '', pen = 'M';
      for (let i = 0; i <= 400; i++) {
        const u = i / 400, x = logX ? 10 ** (Math.log10(xs[0]) + u * (Math.log10(xs[xs.length - 1]) - Math.log10(xs[0]))) : Math.min(...xs) + u * (Math.max(...xs) - Math.min(...xs));
        const y = s.reference(x, f);
        if (Number.isFinite(y) && (!logY || y > 0)) { d += `${pen}${X.at(x).toFixed(2)},${Y.at(y).toFixed(2)}`; pen = 'L'; } else pen = 'M';
      }
      svg.append(el('path', { class: 'reference', d, fill: 'none', stroke: REF, 'stroke-width': 2, 'stroke-dasharray': '6 4' }));
    }
    const clip = el('clipPath', { id: 'sweep-curve-clip' });
    clip.append(el('rect', { x: c.l, y: c.t, width: c.pw, height: c.ph }));
    svg.append(clip);
    const groups = new Map(); // the second parameter's index -> its runs
    for (const r of ok) {
      const g = axes.length === 2 ? r.index % axes[1].values.length : 0;
      if (!groups.has(g)) groups.set(g, []);
      groups.get(g).push(r);
    }
    const bottom = c.t + c.ph - 6;
    for (const [g, rs] of [...groups.entries()].sort((a, b) => a[0] - b[0])) {
      rs.sort((a, b) => a.values[0] - b.values[0]);
      const col = axes.length === 2 ? family(g, axes[1].values.length) : INK;
      svg.append(el('path', { class: 'curve', d: rs.map((r, i) => `${i ? 'L' : 'M'}${X.at(r.values[0]).toFixed(2)},${Y.at(r.features[f]).toFixed(2)}`).join(''),
        fill: 'none', stroke: col, 'stroke-width': 1.5, 'stroke-linejoin': 'round', 'clip-path': 'url(#sweep-curve-clip)' }));
      for (const r of rs) {
        const dot = el('circle', { class: 'pt', 'data-index': r.index, 'data-x': r.values[0], 'data-y': r.features[f],
          cx: X.at(r.values[0]).toFixed(2), cy: Y.at(r.features[f]).toFixed(2), r: 3.5, fill: col, cursor: 'pointer' });
        dot.append(el('title', {}, this.describe(r, f)));
        svg.append(dot);
      }
    }
    for (const r of runs) {
      if (!r.status && typeof r.features[f] === 'number') continue;
      const x = X.at(r.values[0]);
      const mk = r.status ? cross(x, bottom, 'failed', r.index)
        : el('circle', { class: 'null', 'data-index': r.index, cx: x, cy: bottom, r: 3.5, fill: '#fff', stroke: NULLC, 'stroke-width': 1.5 });
      mk.append(el('title', {}, this.describe(r, f)));
      svg.append(mk);
    }
    if (this.hot !== null && s.runs.has(this.hot)) {
      const r = s.runs.get(this.hot), y = !r.status && typeof r.features[f] === 'number' ? Y.at(r.features[f]) : bottom;
      svg.append(el('circle', { class: 'hot', cx: X.at(r.values[0]), cy: y, r: 7, fill: 'none', stroke: INK, 'stroke-width': 1.5 }));
    }
    svg.append(frame(c));
    svg.dataset.points = String(ok.length);
    this.curveScale = { X, Y, f, bottom };
    const legend = $('sweep-curve-legend');
    const items = axes.length === 2 ? axes[1].values.map((v, i) => [family(i, axes[1].values.length), `${paramName(axes[1].pointer)} = ${fmt(v)}`, 'line']) : [[INK, f, 'line']];
    if (s.reference) items.push([REF, s.reference.label || 'closed form', 'dash']);
    if (runs.some((r) => !r.status && r.features[f] === null)) items.push([NULLC, `${f} null (no value: hover for why)`, 'null']);
    if (s.failed.length) items.push([FAIL, 'failed run', 'fail']);
    legend.replaceChildren(...items.map(([c2, t, k]) => entry(c2, t, k)));
  }

  // The section points' x against the first parameter (a Poincaré section per run: a bifurcation diagram).
  drawBifurcation(axes) {
    const svg = $('sweep-bif'), s = this.s, c = chart(svg);
    const runs = [...s.runs.values()].filter((r) => !r.status && Array.isArray(r.section));
    const xs = axes.length ? axes[0].values : [0, 1];
    const pts = runs.flatMap((r) => r.section.map((p) => p[1]));
    const X = scale(Math.min(...xs), Math.max(...xs), this.logAxis(0), c.l, c.pw, false);
    const Y = scale(pts.length ? Math.min(...pts) : -1, pts.length ? Math.max(...pts) : 1, false, c.t, c.ph, true);
    axis(c, 'x', X.ticks, axes.length ? `${paramName(axes[0].pointer)}  (${axes[0].pointer})` : 'parameter');
    axis(c, 'y', Y.ticks, 'x at the section');
    const two = axes.length === 2, paths = new Map();
    for (const r of runs) {
      const g = two ? r.index % axes[1].values.length : 0, px = X.at(r.values[0]);
      let d = paths.get(g) || '';
      for (const p of r.section) d += `M${(px - 1).toFixed(1)},${(Y.at(p[1]) - 1).toFixed(1)}h2v2h-2z`;
      paths.set(g, d);
    }
    for (const [g, d] of paths) svg.append(el('path', { class: 'section', d, fill: two ? family(g, axes[1].values.length) : INK }));
    for (const r of s.failed) svg.append(cross(X.at(r.values[0]), c.t + c.ph - 6, 'failed', r.index));
    const sec = s.meta && s.meta.record.section;
    if (sec && s.summary && !pts.length) svg.append(el('text', { x: c.l + c.pw / 2, y: c.t + c.ph / 2, 'text-anchor': 'middle', fill: SOFT, 'font-size': 13 },
      `no run has a section point (no ${sec.event || 'section'} event after record.after)`));
    if (this.hot !== null && s.runs.has(this.hot)) {
      const x = X.at(s.runs.get(this.hot).values[0]);
      svg.append(el('line', { class: 'hot', x1: x, x2: x, y1: c.t, y2: c.t + c.ph, stroke: INK, 'stroke-dasharray': '3 3' }));
    }
    svg.append(frame(c));
    svg.dataset.points = String(pts.length);
    this.bifScale = { X };
    $('sweep-bif-legend').textContent = sec ? (sec.event ? `one point at each ${sec.event} event after t = ${fmt(s.meta.record.after)}`
      : `stroboscopic: t = ${fmt(s.meta.record.after)} + k \u00b7 ${fmt(sec.period)}`) : '';
  }

  // Two parameters: the feature coloured over the grid (first parameter across, second up), one cell a run.
  drawMap(f, axes) {
    const svg = $('sweep-map'), s = this.s, c = chart(svg, 90);
    const [n0, n1] = [axes[0].values.length, axes[1].values.length];
    const runs = [...s.runs.values()], vals = runs.filter((r) => !r.status && typeof r.features[f] === 'number').map((r) => r.features[f]);
    const log = $('sweep-log').checked && vals.length > 0 && vals.every((v) => v > 0);
    const t = (v) => (log ? Math.log10(v) : v);
    const lo = vals.length ? Math.min(...vals.map(t)) : 0, hi = vals.length ? Math.max(...vals.map(t)) : 1;
    const cw = c.pw / n0, ch = c.ph / n1;
    const tick = (n, at, values) => {
      const step = Math.max(1, Math.ceil(n / Math.max(2, Math.round((at === 'x' ? c.pw / 90 : c.ph / 40)))));
      const out = [];
      for (let i = 0; i < n; i += step) out.push({ at: at === 'x' ? c.l + (i + 0.5) * cw : c.t + c.ph - (i + 0.5) * ch, label: fmt(values[i]) });
      return out;
    };
    axis(c, 'x', tick(n0, 'x', axes[0].values), `${paramName(axes[0].pointer)}  (${axes[0].pointer})`);
    axis(c, 'y', tick(n1, 'y', axes[1].values), `${paramName(axes[1].pointer)}  (${axes[1].pointer})`);
    let cells = 0;
    for (const r of runs) {
      const i0 = Math.floor(r.index / n1), i1 = r.index % n1, x = c.l + i0 * cw, y = c.t + c.ph - (i1 + 1) * ch;
      const v = !r.status ? r.features[f] : undefined;
      const cell = el('rect', { class: r.status ? 'failed cell' : typeof v === 'number' ? 'cell' : 'null cell', 'data-index': r.index,
        x: x.toFixed(2), y: y.toFixed(2), width: (cw + 0.5).toFixed(2), height: (ch + 0.5).toFixed(2), cursor: 'pointer',
        fill: r.status ? '#fdecea' : typeof v === 'number' ? viridis(hi > lo ? (t(v) - lo) / (hi - lo) : 0.5) : '#e4e7ec' });
      cell.append(el('title', {}, this.describe(r, f)));
      svg.append(cell);
      if (r.status) svg.append(cross(x + cw / 2, y + ch / 2, 'failed', r.index));
      if (typeof v === 'number') cells++;
    }
    const bar = { x: c.l + c.pw + 18, w: 14 }; // the colour bar, with the feature's ticks
    for (let k = 0; k < 64; k++)
      svg.append(el('rect', { x: bar.x, y: c.t + c.ph * (1 - (k + 1) / 64), width: bar.w, height: c.ph / 64 + 0.5, fill: viridis((k + 0.5) / 64) }));
    if (vals.length) {
      const B = scale(log ? 10 ** lo : lo, log ? 10 ** hi : hi, log, c.t, c.ph, true);
      const inv = (v) => (log ? Math.log10(v) : v);
      const [blo, bhi] = [lo, hi]; // the bar spans the data exactly
      for (const tk of B.ticks) {
        const v = tk.label.replace('\u2212', '-') * 1;
        const u = bhi > blo ? (inv(v) - blo) / (bhi - blo) : 0.5;
        if (u < -1e-9 || u > 1 + 1e-9) continue;
        const y = c.t + c.ph * (1 - u);
        svg.append(el('line', { x1: bar.x + bar.w, x2: bar.x + bar.w + 4, y1: y, y2: y, stroke: FRAME }),
          el('text', { class: 'tick', x: bar.x + bar.w + 6, y: y + 4, 'font-size': 12, fill: SOFT }, tk.label));
      }
    }
    svg.append(frame(c));
    svg.dataset.points = String(cells);
    this.mapGrid = { c, n0, n1, cw, ch };
    $('sweep-map-legend').textContent = `${f}${log ? ' (log)' : ''} over the grid: one cell a run, grey null, red failed`;
  }

  // The axis of parameter j is logarithmic when the document's vary says so.
  logAxis(j) {
    const v = this.s && this.s.doc && Array.isArray(this.s.doc.vary) ? this.s.doc.vary[j] : null;
    return !!(v && v.scale === 'log' && this.axes()[j] && this.axes()[j].values.every((x) => x > 0));
  }

  describe(r, f) {
    const axes = this.axes();
    const at = r.values.map((v, j) => `${axes[j] ? paramName(axes[j].pointer) : 'p' + j} = ${fmt(v)}`).join(', ');
    if (r.status) return `run ${r.index} (${at}) failed: ${r.status} ${r.title || ''}${r.detail ? ' \u2014 ' + r.detail : ''}` +
      (r.errors ? ' ' + r.errors.map((e) => `${e.pointer} ${e.detail || e.message || ''}`).join('; ') : '');
    const v = r.features[f];
    return `run ${r.index} (${at}): ${f} = ${v === null ? 'null, ' + ((r.null && r.null[f]) || 'no value') : fmt(v)}`;
  }

  // The failed runs, listed with their problems (pointers into the base).
  list() {
    const box = $('sweep-failed'), s = this.s;
    box.hidden = !s.failed.length && !s.error;
    const items = s.failed.map((r) => {
      const li = document.createElement('li'), b = document.createElement('button');
      b.type = 'button';
      b.className = 'link';
      b.textContent = `run ${r.index}`;
      b.addEventListener('click', () => this.open(r.index));
      li.append(b, ' ' + this.describe(r, $('sweep-feature').value).replace(/^run \d+ /, ''));
      return li;
    });
    if (s.error) {
      const li = document.createElement('li');
      li.textContent = `The sweep stopped: ${s.error.status || ''} ${s.error.title || ''}${s.error.detail ? ' \u2014 ' + s.error.detail : ''}`;
      items.push(li);
    }
    $('sweep-failed-title').textContent = s.failed.length ? `${s.failed.length} run${s.failed.length === 1 ? '' : 's'} failed (each a line, the sweep went on):` : '';
    $('sweep-failed-list').replaceChildren(...items);
  }

  info() {
    const s = this.s;
    if (!s) return;
    const m = s.meta, runs = s.runs.size;
    let t = m ? `${runs} of ${m.selected} runs` + (m.selected !== m.runs ? ` (of a grid of ${m.runs})` : '') +
      (m.axes.length === 2 ? ` on a ${m.axes[0].values.length} \u00d7 ${m.axes[1].values.length} grid` : '') : 'waiting for the meta line\u2026';
    if (s.summary) t += ` \u00b7 ${s.summary.completed} completed, ${s.summary.failed} failed, ${s.summary.steps.toLocaleString('en')} steps`;
    $('sweep-info').textContent = t;
    const hot = this.hot !== null && s.runs.get(this.hot);
    $('sweep-hover').textContent = hot ? this.describe(hot, $('sweep-feature').value) + ' \u2014 click: its trajectory'
      : runs ? 'Point at a run to read it; click it to open its trajectory.' : '';
  }

  // The run under the pointer: the nearest dot of the curve (within 24 px), the nearest column of the
  // diagram, the cell of the map.
  nearest(svg, e) {
    const s = this.s;
    if (!s || !s.runs.size) return null;
    const box = svg.getBoundingClientRect(), vb = svg.viewBox.baseVal;
    const px = (e.clientX - box.left) * (vb.width / box.width), py = (e.clientY - box.top) * (vb.height / box.height);
    if (svg.id === 'sweep-map') {
      const g = this.mapGrid;
      if (!g) return null;
      const i0 = Math.floor((px - g.c.l) / g.cw), i1 = Math.floor((g.c.t + g.c.ph - py) / g.ch);
      const i = i0 * g.n1 + i1;
      return i0 >= 0 && i0 < g.n0 && i1 >= 0 && i1 < g.n1 && s.runs.has(i) ? i : null;
    }
    let best = null, bd = Infinity;
    for (const r of s.runs.values()) {
      let d;
      if (svg.id === 'sweep-bif') d = Math.abs(this.bifScale.X.at(r.values[0]) - px);
      else {
        const { X, Y, f, bottom } = this.curveScale, y = !r.status && typeof r.features[f] === 'number' ? Y.at(r.features[f]) : bottom;
        d = Math.hypot(X.at(r.values[0]) - px, y - py);
      }
      if (d < bd) { bd = d; best = r.index; }
    }
    return bd <= 24 ? best : null;
  }

  hover(svg, e) {
    const i = this.nearest(svg, e);
    if (i === this.hot) return;
    this.hot = i;
    this.schedule();
  }

  // Opens run i in the trajectory view: the base with the run's values at the pointers.
  open(i) {
    const s = this.s, r = s && s.runs.get(i);
    if (!r || !s.doc || !s.doc.base) return;
    const axes = this.axes(), ptrs = axes.map((a) => a.pointer);
    const label = `Run ${i} of the sweep: ` + r.values.map((v, j) => `${ptrs[j]} = ${v}`).join(', ') +
      (r.status ? ' (it failed in the sweep: the daemon says why)' : '');
    const doc = putValues(s.doc.base, ptrs, r.values);
    // A sweep's run is long (a transient, then the motion): the page's usual budget of about a plot's width
    // of samples would alias the forcing's periods, so ask for the daemon's default number, 10 001. Output
    // decides which records are written, never how the solver steps: the run is the sweep's.
    if (!doc.output) doc.output = { max_samples: 10001 };
    this.opener(doc, label);
  }
}

// The features offered: those the sweep's lines carry, the one picked kept when it is among them.
function featureOptions(feats) {
  const sel = $('sweep-feature');
  if ([...sel.options].map((o) => o.value).join() === feats.join()) return;
  const keep = sel.value;
  sel.replaceChildren(...feats.map((f) => new Option(f, f)));
  if (feats.includes(keep)) sel.value = keep;
}

// A legend entry: a swatch (a line, dashed, an open dot or a cross) in a colour, then the text.
function entry(color, text, kind) {
  const span = document.createElement('span'), sw = document.createElement('i');
  sw.className = kind === 'dash' ? 'sw dash' : kind === 'line' ? 'sw' : 'mk';
  if (kind === 'null' || kind === 'fail') sw.textContent = kind === 'null' ? '\u25cb' : '\u00d7';
  sw.style.color = color; // CSSOM, not markup: the CSP refuses inline style attributes
  span.append(sw, text);
  return span;
}
