// web/quakes.js - the Gutenberg-Richter plot of a network run's quake catalogue (docs/quakes.md): with
// "output": {"quakes": true} the stream carries a "quake" line per slip episode; this keeps their magnitudes
// mu = ln(moment) and draws log10 of the count per magnitude bin against mu, with the least-squares line
// through the non-empty bins and its slope. Kept apart from network.js: app.js hands each quake line to
// push() and asks draw() to paint; the figure shows only when a run has quakes.
//
// For tests, #plot-quakes carries data-quakes (quake lines received), data-bins (non-empty bins drawn) and
// data-slope (the fitted slope, "" with fewer than two bins).

import { niceStep, tickLabel } from './plot.js';

const $ = (id) => document.getElementById(id);
const BINS = 24;

// Histogram of the finite magnitudes over BINS bins, and the least-squares line of log10(count) over the
// non-empty ones: {centres, counts, slope, intercept} (slope NaN with fewer than two bins).
export function gutenbergRichter(mu, bins = BINS) {
  const m = mu.filter(Number.isFinite);
  if (!m.length) return { centres: [], counts: [], slope: NaN, intercept: NaN };
  let lo = Math.min(...m), hi = Math.max(...m);
  if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
  const w = (hi - lo) / bins, counts = new Array(bins).fill(0);
  for (const v of m) counts[Math.min(bins - 1, Math.floor((v - lo) / w))]++;
  const centres = counts.map((_, i) => lo + (i + 0.5) * w);
  let n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  counts.forEach((c, i) => {
    if (c === 0) return;
    const x = centres[i], y = Math.log10(c);
    n++; sx += x; sy += y; sxx += x * x; sxy += x * y;
  });
  const d = n * sxx - sx * sx;
  const slope = n >= 2 && d > 0 ? (n * sxy - sx * sy) / d : NaN;
  return { centres, counts, slope, intercept: (sy - slope * sx) / n };
}

export class QuakeView {
  constructor() {
    this.canvas = $('plot-quakes');
    this.figure = $('quakes-figure');
    this.reset();
    if (this.canvas) new ResizeObserver(() => this.draw()).observe(this.canvas);
  }

  reset() {
    this.mu = [];
    this.quakes = 0;
    if (this.figure) this.figure.hidden = true;
  }

  push(o) {
    this.quakes++;
    if (typeof o.magnitude === 'number') this.mu.push(o.magnitude);
  }

  draw() {
    const canvas = this.canvas;
    if (!canvas) return;
    this.figure.hidden = this.quakes === 0;
    const dpr = window.devicePixelRatio || 1, w = canvas.clientWidth, h = canvas.clientHeight;
    canvas.dataset.quakes = String(this.quakes);
    if (w === 0 || h === 0) return;
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
    const ctx = canvas.getContext('2d');
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, w, h);
    const gr = gutenbergRichter(this.mu);
    const pts = gr.centres.map((x, i) => [x, gr.counts[i]]).filter(([, c]) => c > 0).map(([x, c]) => [x, Math.log10(c)]);
    canvas.dataset.bins = String(pts.length);
    canvas.dataset.slope = Number.isFinite(gr.slope) ? String(gr.slope) : '';
    const m = { l: 62, r: 14, t: 10, b: 42 }, pw = w - m.l - m.r, ph = h - m.t - m.b;
    const xs = pts.map((p) => p[0]), ys = pts.map((p) => p[1]);
    const xlo = xs.length ? Math.min(...xs) - 0.5 : 0, xhi = xs.length ? Math.max(...xs) + 0.5 : 1;
    const ylo = 0, yhi = Math.max(1, ...ys) + 0.2;
    const X = (x) => m.l + ((x - xlo) / (xhi - xlo)) * pw, Y = (y) => m.t + ph - ((y - ylo) / (yhi - ylo)) * ph;
    const ink = getComputedStyle(document.body).color || '#222';
    ctx.strokeStyle = ctx.fillStyle = ink;
    ctx.font = '12px system-ui, sans-serif';
    ctx.strokeRect(m.l, m.t, pw, ph);
    const sx = niceStep(xlo, xhi, Math.max(2, Math.round(pw / 90))), sy = niceStep(ylo, yhi, Math.max(2, Math.round(ph / 48)));
    ctx.textAlign = 'center';
    for (let x = Math.ceil(xlo / sx) * sx; x <= xhi; x += sx) ctx.fillText(tickLabel(x, sx), X(x), m.t + ph + 16);
    ctx.textAlign = 'right';
    for (let y = Math.ceil(ylo / sy) * sy; y <= yhi; y += sy) ctx.fillText(tickLabel(y, sy), m.l - 6, Y(y) + 4);
    ctx.textAlign = 'center';
    ctx.fillText('magnitude \u03bc = ln(moment)', m.l + pw / 2, h - 4);
    ctx.save();
    ctx.translate(14, m.t + ph / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.fillText('log\u2081\u2080 count per bin', 0, 0);
    ctx.restore();
    ctx.fillStyle = '#0072b2';
    for (const [x, y] of pts) { ctx.beginPath(); ctx.arc(X(x), Y(y), 3.5, 0, 2 * Math.PI); ctx.fill(); }
    const legend = $('quakes-legend');
    if (Number.isFinite(gr.slope)) {
      ctx.strokeStyle = '#d55e00';
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      ctx.moveTo(X(xs[0]), Y(gr.intercept + gr.slope * xs[0]));
      ctx.lineTo(X(xs[xs.length - 1]), Y(gr.intercept + gr.slope * xs[xs.length - 1]));
      ctx.stroke();
    }
    if (legend) legend.textContent = `${this.quakes} quakes` +
      (Number.isFinite(gr.slope) ? `, fitted slope ${gr.slope.toPrecision(3)} per unit of \u03bc` : '');
  }
}
