// web/modes.js - the modes tab: a network's natural frequencies as bars, its mass-normalized mode shapes drawn
// over the node index, and the receptance of one node to a harmonic force at another on log-log axes with its
// resonances and antiresonances marked (POST v1/modes and v1/response, docs/modes.md).
//
// Drawn as SVG (the text is text: each tick label a <text> of its axis, readable and selectable), with the
// page's conventions: every axis has ticks, tick labels and a title; a log axis is labelled at its decades
// (plain numbers from 0.001 to 1000, 10 with a superscript exponent beyond) and, when it spans less than two
// decades, at 2 and 5 times them too; each figure has a legend. The charts are drawn again when they resize.
//
// For tests: the panel's dataset says what was drawn (data-modes, data-resonances, data-antiresonances); each
// <svg> carries data-points (bars, shape points or response points drawn); its axes are <g class="axis x">
// and <g class="axis y">, the tick labels <text class="tick">, the plot frame <rect class="frame">, the
// bar values <text class="value">.

import { niceStep, tickLabel } from './plot.js';

const NS = 'http://www.w3.org/2000/svg';
const COLOURS = ['#1f6feb', '#d1242f', '#1a7f37', '#8250df', '#bf8700', '#0a7e8c'];
const INK = '#1d2433', SOFT = '#5b6475', GRID = '#eceef2', FRAME = '#b9c0cc', ZERO = '#c3c8d1';
const RES = '#d1242f', ANTI = '#1f6feb';
const MARGIN = { l: 62, r: 14, t: 10, b: 42 };
const colour = (i) => COLOURS[i % COLOURS.length];
const $ = (id) => document.getElementById(id);

// An SVG element with attributes (presentation attributes, never style: the CSP refuses inline styles).
function el(tag, attrs = {}, text) {
  const e = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

// A clear <svg> of its box's size, with the plot area's rectangle and scales to fill in.
function chart(svg) {
  const w = Math.max(120, svg.clientWidth), h = Math.max(120, svg.clientHeight);
  svg.replaceChildren();
  svg.setAttribute('viewBox', `0 0 ${w} ${h}`);
  svg.setAttribute('font-family', 'system-ui, sans-serif');
  const m = MARGIN;
  return { svg, w, h, l: m.l, t: m.t, pw: w - m.l - m.r, ph: h - m.t - m.b };
}

// A number as a tick label: plain from 0.001 to 1000 (no exponent), else 10 or d×10 with a superscript.
function logLabel(text, k, mant) {
  if (k >= -3 && k <= 3) {
    text.textContent = String(+(mant * 10 ** k).toPrecision(3));
    return;
  }
  text.textContent = mant === 1 ? '10' : `${mant}\u00d710`;
  text.append(el('tspan', { dy: '-0.55em', 'font-size': '0.78em' }, String(k).replace('-', '\u2212')));
}

// Ticks of a log10 axis over [lo, hi] (exponents): the decades, and 2 and 5 times them when there are few.
function logTicks(lo, hi) {
  const decades = [];
  for (let k = Math.ceil(lo - 1e-9); k <= hi + 1e-9; k++) decades.push({ v: k, k, mant: 1 });
  const fine = [];
  for (let k = Math.floor(lo) - 1; k <= Math.ceil(hi); k++)
    for (const mant of [2, 5]) { const v = k + Math.log10(mant); if (v >= lo - 1e-9 && v <= hi + 1e-9) fine.push({ v, k, mant }); }
  const minor = [];
  for (let k = Math.floor(lo) - 1; k <= Math.ceil(hi); k++)
    for (let mant = 2; mant <= 9; mant++) { const v = k + Math.log10(mant); if (v >= lo && v <= hi) minor.push(v); }
  return { labelled: decades.length >= 3 ? decades : [...decades, ...fine].sort((a, b) => a.v - b.v), minor };
}

// Grid lines, ticks and labels of one axis. ticks: [{at (pixel), label (text or a function filling a <text>)}].
function axis(c, which, ticks, title, minor = []) {
  const g = el('g', { class: `axis ${which}`, 'font-size': 12, fill: SOFT });
  const { l, t, pw, ph } = c;
  for (const at of minor) {
    g.append(which === 'x' ? el('line', { x1: at, x2: at, y1: t + ph, y2: t + ph - 4, stroke: FRAME })
      : el('line', { x1: l, x2: l + 4, y1: at, y2: at, stroke: FRAME }));
  }
  for (const { at, label } of ticks) {
    const p = Math.round(at) + 0.5;
    if (which === 'x') {
      g.append(el('line', { x1: p, x2: p, y1: t, y2: t + ph, stroke: GRID }), el('line', { x1: p, x2: p, y1: t + ph, y2: t + ph + 4, stroke: FRAME }));
      const txt = el('text', { class: 'tick', x: p, y: t + ph + 17, 'text-anchor': 'middle' });
      typeof label === 'function' ? label(txt) : (txt.textContent = label);
      g.append(txt);
    } else {
      g.append(el('line', { x1: l, x2: l + pw, y1: p, y2: p, stroke: GRID }), el('line', { x1: l - 4, x2: l, y1: p, y2: p, stroke: FRAME }));
      const txt = el('text', { class: 'tick', x: l - 7, y: p + 4, 'text-anchor': 'end' });
      typeof label === 'function' ? label(txt) : (txt.textContent = label);
      g.append(txt);
    }
  }
  const name = which === 'x'
    ? el('text', { class: 'title', x: l + pw / 2, y: c.h - 5, 'text-anchor': 'middle', 'font-style': 'italic', 'font-size': 13, fill: INK }, title)
    : el('text', { class: 'title', transform: `translate(15 ${t + ph / 2}) rotate(-90)`, 'text-anchor': 'middle', 'font-style': 'italic',
      'font-size': 13, fill: INK }, title);
  g.append(name);
  c.svg.append(g);
}

// Linear ticks over [lo, hi] (already nice), mapped by `at`.
function linearTicks(lo, hi, count, at) {
  const s = niceStep(lo, hi, count), out = [];
  for (let v = Math.ceil(lo / s - 1e-9) * s; v <= hi + s * 1e-9; v += s) {
    const x = Math.abs(v) < s * 1e-9 ? 0 : v;
    out.push({ at: at(x), label: tickLabel(x, s).replace(/-/g, '\u2212') });
  }
  return out;
}

const frameRect = (c) => el('rect', { class: 'frame', x: c.l + 0.5, y: c.t + 0.5, width: c.pw - 1, height: c.ph - 1, fill: 'none', stroke: FRAME });

// Bars of the frequencies (rad/s), one per mode in its colour, on an ω axis with ticks; each bar's value
// above it, inside the frame (the axis reaches a tick above the highest bar and its label).
function drawBars(svg, modes) {
  const c = chart(svg), n = modes.length;
  const peak = Math.max(...modes.map((m) => m.omega), 1e-12);
  const yticks = Math.max(2, Math.round(c.ph / 48));
  const s = niceStep(0, peak * 1.18, yticks), top = Math.ceil((peak * 1.18) / s) * s; // room for the value labels
  const Y = (v) => c.t + c.ph * (1 - v / top), bw = c.pw / Math.max(n, 1);
  axis(c, 'y', linearTicks(0, top, yticks, Y), '\u03c9 (rad/s)');
  axis(c, 'x', modes.map((_, i) => ({ at: c.l + (i + 0.5) * bw, label: String(i + 1) })), 'mode');
  modes.forEach((m, i) => {
    const y = Y(m.omega), x = c.l + i * bw + bw * 0.2;
    svg.append(el('rect', { class: 'bar', x, y, width: bw * 0.6, height: c.t + c.ph - y, fill: colour(i) }));
    svg.append(el('text', { class: 'value', x: x + bw * 0.3, y: Math.max(y - 5, c.t + 14), 'text-anchor': 'middle', 'font-size': 12, fill: INK },
      +m.omega.toPrecision(4) + ''));
  });
  svg.append(frameRect(c));
  svg.dataset.points = String(n);
}

// The shapes: node on x (each node a tick), the mass-normalized amplitude on y (ticks, zero line), one
// polyline per mode in its colour with a dot at each node.
function drawShapes(svg, modes) {
  const c = chart(svg), n = modes.length ? modes[0].shape.length : 0;
  const yticks = Math.max(2, Math.round(c.ph / 48));
  const peak = Math.max(...modes.flatMap((m) => m.shape.map(Math.abs)), 1e-12);
  const s = niceStep(-peak, peak, yticks), top = Math.ceil(peak / s - 1e-9) * s;
  const X = (j) => c.l + c.pw * (n > 1 ? (0.04 + 0.92 * j / (n - 1)) : 0.5);
  const Y = (a) => c.t + c.ph * (0.5 - a / (2 * top));
  axis(c, 'y', linearTicks(-top, top, yticks, Y), 'amplitude');
  axis(c, 'x', Array.from({ length: n }, (_, j) => ({ at: X(j), label: String(j) })), 'node');
  svg.append(el('line', { x1: c.l, x2: c.l + c.pw, y1: Y(0), y2: Y(0), stroke: ZERO }));
  let points = 0;
  modes.forEach((m, i) => {
    svg.append(el('polyline', { class: 'shape', points: m.shape.map((a, j) => `${X(j)},${Y(a)}`).join(' '), fill: 'none', stroke: colour(i),
      'stroke-width': 2 }));
    for (const [j, a] of m.shape.entries()) { svg.append(el('circle', { class: 'node', cx: X(j), cy: Y(a), r: 3.5, fill: colour(i) })); points++; }
  });
  svg.append(frameRect(c));
  svg.dataset.points = String(points);
}

// |H(ω)| on log-log axes labelled at their decades, the resonances (red) and antiresonances (blue) dashed.
function drawResponse(svg, resp) {
  const c = chart(svg);
  const rows = resp.rows.filter((r) => r.omega > 0 && r.magnitude > 0);
  if (rows.length < 2) { svg.dataset.points = '0'; return; }
  const lx = rows.map((r) => Math.log10(r.omega)), ly = rows.map((r) => Math.log10(r.magnitude));
  const x0 = Math.min(...lx), x1 = Math.max(...lx);
  const pad = 0.04 * (Math.max(...ly) - Math.min(...ly) || 1), y0 = Math.min(...ly) - pad, y1 = Math.max(...ly) + pad;
  const X = (v) => c.l + c.pw * (v - x0) / (x1 - x0 || 1);
  const Y = (v) => c.t + c.ph * (1 - (v - y0) / (y1 - y0 || 1));
  const ticks = (lo, hi, at) => {
    const { labelled, minor } = logTicks(lo, hi);
    return { ticks: labelled.map((k) => ({ at: at(k.v), label: (txt) => logLabel(txt, k.k, k.mant) })), minor: minor.map(at) };
  };
  const tx = ticks(x0, x1, X), ty = ticks(y0, y1, Y);
  axis(c, 'x', tx.ticks, '\u03c9 (rad/s)', tx.minor);
  axis(c, 'y', ty.ticks, '|H(\u03c9)|', ty.minor);
  const mark = (omega, colour, cls) => {
    if (!(omega > 0)) return;
    const x = X(Math.log10(omega));
    if (x < c.l || x > c.l + c.pw) return;
    svg.append(el('line', { class: cls, x1: x, x2: x, y1: c.t, y2: c.t + c.ph, stroke: colour, 'stroke-dasharray': '4 3' }));
  };
  (resp.resonances || []).forEach((r) => mark(r.omega, RES, 'resonance'));
  (resp.antiresonances || []).forEach((r) => mark(r.omega, ANTI, 'antiresonance'));
  svg.append(el('path', { class: 'curve', d: rows.map((_, i) => `${i ? 'L' : 'M'}${X(lx[i]).toFixed(2)},${Y(ly[i]).toFixed(2)}`).join(''),
    fill: 'none', stroke: INK, 'stroke-width': 2, 'stroke-linejoin': 'round' }));
  svg.append(frameRect(c));
  svg.dataset.points = String(rows.length);
}

// A legend entry: a swatch (a line, dashed or not, or a square) in a colour, then the text.
function entry(color, text, kind = 'line') {
  const span = document.createElement('span'), sw = document.createElement('i');
  sw.className = kind === 'line' ? 'sw' : kind === 'dash' ? 'sw dash' : 'sw box';
  sw.style.color = color; // CSSOM, not markup: the CSP refuses inline style attributes
  span.append(sw, text);
  return span;
}

// Runs a modes request: v1/modes always, v1/response when the document names force_node and response_node.
// post(route) returns a fetch promise; the answers are returned, the drawing done into the panel's charts.
export async function runModes(post, text) {
  let doc = {};
  try { doc = JSON.parse(text); } catch { /* the daemon says where */ }
  const wantsResponse = doc && doc.force_node !== undefined && doc.response_node !== undefined;
  const [mr, rr] = await Promise.all([post('v1/modes'), wantsResponse ? post('v1/response') : null]);
  return { mr, rr };
}

let shown = null; // the last answers, drawn again when a chart resizes
function draw() {
  if (!shown) return;
  const { modes, resp } = shown;
  drawBars($('modes-bars'), modes.modes);
  drawShapes($('modes-shapes'), modes.modes);
  if (resp) drawResponse($('modes-response'), resp);
}
const resized = new ResizeObserver(() => draw());

export function renderModes(modes, resp) {
  const panel = $('panel-modes');
  shown = { modes, resp };
  $('modes-response').closest('figure').hidden = !resp;
  $('modes-bars-legend').replaceChildren(...modes.modes.map((m, i) => entry(colour(i), `mode ${i + 1}`, 'box')));
  $('modes-shapes-legend').replaceChildren(...modes.modes.map((m, i) =>
    entry(colour(i), `mode ${i + 1}, \u03c9 = ${+m.omega.toPrecision(4)}`)));
  if (resp) $('modes-response-legend').replaceChildren(entry(INK, `node ${resp.response_node}, force at node ${resp.force_node}`),
    entry(RES, 'resonance', 'dash'), entry(ANTI, 'antiresonance', 'dash'));
  draw();
  for (const id of ['modes-bars', 'modes-shapes', 'modes-response']) resized.observe($(id));
  panel.dataset.modes = String(modes.modes.length);
  panel.dataset.resonances = resp ? String((resp.resonances || []).length) : '';
  panel.dataset.antiresonances = resp ? String((resp.antiresonances || []).length) : '';
  const left = (modes.left_out || []).length;
  $('modes-info').textContent =
    `${modes.modes.length} modes of ${modes.nodes} nodes` + (left ? `; ${left} set-valued element(s) left out` : '') +
    (modes.damped ? '; damped eigenvalues computed' : '');
}
