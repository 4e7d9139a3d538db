// web/network.js - the page's view of a network run (docs/networks.md): a model with `masses` or
// `mass_matrix` streams samples of arrays over the columns its meta line lists. Kept apart from app.js so
// the one-mass page stays as it is: app.js hands the meta line to start(), each sample to push(), and
// asks draw() to paint. What is drawn: a space-time picture (written node × time, coloured by velocity,
// the stuck blocks of a chain on a belt in one flat colour), and per-node curves x_i(t), v_i(t) of up to
// eight nodes spread over the chain.
//
// For tests, #network-plots carries data-nodes (columns written), data-curves (nodes drawn as curves) and
// each canvas data-points (the samples its last drawing went through), as the one-mass plots do; the
// space-time canvas also data-area (left, top, width, height of the picture in CSS pixels).

import { Table, Plot, niceStep } from './plot.js';

const $ = (id) => document.getElementById(id);
const MAX_CURVES = 8;
const MAX_CELLS = 8e6; // numbers held for plotting (64 MB); a longer run is drawn up to there
// Okabe-Ito, colour-blind safe, for the per-node curves
const PALETTE = ['#0072b2', '#d55e00', '#009e73', '#cc79a7', '#e69f00', '#56b4e9', '#7a5cc4', '#000000'];
// viridis at nine stops: dark (slow) to yellow (fast); one hue order so a stuck row reads as one band
const VIRIDIS = [[68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142], [31, 158, 137],
  [53, 183, 121], [109, 205, 89], [180, 222, 44], [253, 231, 37]];

function viridis(s) {
  const f = Math.min(1, Math.max(0, s)) * (VIRIDIS.length - 1), i = Math.min(VIRIDIS.length - 2, Math.floor(f)), r = f - i;
  const a = VIRIDIS[i], b = VIRIDIS[i + 1];
  return [a[0] + (b[0] - a[0]) * r, a[1] + (b[1] - a[1]) * r, a[2] + (b[2] - a[2]) * r];
}

// The samples of one network run as columns t, x0.., v0.. (indices into the written nodes).
export class NetworkRun {
  constructor(meta, extra = []) { // extra: more columns, filled by a subclass (web/contact.js)
    this.nodes = meta.columns.nodes;
    this.elements = meta.columns.elements;
    const k = this.nodes.length;
    this.table = new Table(['t', ...this.nodes.map((_, j) => 'x' + j), ...this.nodes.map((_, j) => 'v' + j), ...extra]);
    this.maxRows = Math.max(1, Math.floor(MAX_CELLS / (2 * k + 1)));
    const m = Math.min(MAX_CURVES, k); // curves at evenly spread columns, first and last included
    this.curves = [...new Set(Array.from({ length: m }, (_, i) => (m === 1 ? 0 : Math.round((i * (k - 1)) / (m - 1)))))];
    this.row = { t: 0 };
  }

  push(o) {
    if (this.table.n >= this.maxRows) return false;
    const row = this.row;
    row.t = o.t;
    for (let j = 0; j < o.x.length; j++) { row['x' + j] = o.x[j]; row['v' + j] = o.v[j]; }
    this.table.push(row);
    return true;
  }
}

// The space-time picture: one row per written node (node 0 at the top), one pixel column per slice of
// [0, t_end], each showing the last sample at or before its time, coloured by v on the run's own range.
class SpaceTime {
  constructor(canvas) {
    this.canvas = canvas;
    this.run = null;
    this.tEnd = 1;
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  draw() {
    const { canvas, run } = this;
    const dpr = window.devicePixelRatio || 1, w = canvas.clientWidth, h = canvas.clientHeight;
    if (w === 0 || h === 0) return;
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr);
      canvas.height = Math.round(h * dpr);
    }
    const ctx = canvas.getContext('2d');
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, w, h);
    const m = { l: 62, r: 86, t: 10, b: 42 }, pw = Math.max(1, Math.floor(w - m.l - m.r)), ph = h - m.t - m.b;
    const t = run ? run.table : null, n = t ? t.n : 0, k = run ? run.nodes.length : 0;
    let vlo = Infinity, vhi = -Infinity;
    for (let j = 0; j < k; j++) { vlo = Math.min(vlo, t.min['v' + j]); vhi = Math.max(vhi, t.max['v' + j]); }
    if (n > 0 && k > 0) this.paint(ctx, m, pw, ph, vlo, vhi);
    this.axes(ctx, m, pw, ph, k);
    if (n > 0) this.colourBar(ctx, m, pw, ph, vlo, vhi);
    canvas.dataset.points = String(n);
    canvas.dataset.area = [m.l, m.t, pw, ph].join(','); // the picture's rectangle in CSS pixels
  }

  paint(ctx, m, pw, ph, vlo, vhi) {
    const t = this.run.table, n = t.n, k = this.run.nodes.length, ts = t.col.t;
    const img = new ImageData(pw, k), px = img.data, span = vhi - vlo > 0 ? vhi - vlo : 1;
    const slice = this.tEnd / pw;
    let i = 0;
    for (let c = 0; c < pw && c * slice <= ts[n - 1]; c++) { // column c: times (c, c + 1] * slice
      while (i + 1 < n && ts[i + 1] <= (c + 1) * slice) i++;
      for (let j = 0; j < k; j++) {
        const [r, g, b] = viridis((t.col['v' + j][i] - vlo) / span), o = 4 * (j * pw + c);
        px[o] = r; px[o + 1] = g; px[o + 2] = b; px[o + 3] = 255;
      }
    }
    const off = new OffscreenCanvas(pw, k);
    off.getContext('2d').putImageData(img, 0, 0);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(off, m.l, m.t, pw, ph);
  }

  axes(ctx, m, pw, ph, k) {
    ctx.font = '12px system-ui, sans-serif';
    ctx.fillStyle = getComputedStyle(document.documentElement).getPropertyValue('--ink-soft').trim() || '#555';
    ctx.strokeStyle = ctx.fillStyle;
    ctx.lineWidth = 1;
    ctx.strokeRect(m.l + 0.5, m.t + 0.5, pw - 1, ph - 1);
    const ticks = (count, lo, hi, at, label) => {
      const s = niceStep(lo, hi, count);
      for (let v = Math.ceil(lo / s) * s; v <= hi + s * 1e-9; v += s) label(at(v), +v.toPrecision(10));
    };
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    ticks(Math.max(2, Math.round(pw / 90)), 0, this.tEnd, (v) => m.l + (v / this.tEnd) * pw, (x, v) => ctx.fillText(String(v), x, m.t + ph + 5));
    ctx.textAlign = 'right';
    ctx.textBaseline = 'middle';
    if (k > 0) {
      const nodes = this.run.nodes;
      ticks(Math.max(2, Math.min(k, Math.round(ph / 40))), 0, k - 1, (j) => m.t + ((j + 0.5) / k) * ph,
        (y, j) => { if (Number.isInteger(j) && j < k) ctx.fillText(String(nodes[j]), m.l - 6, y); });
    }
    ctx.font = 'italic 13px system-ui, sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'bottom';
    ctx.fillText('t', m.l + pw / 2, this.canvas.clientHeight - 4);
    ctx.save();
    ctx.translate(14, m.t + ph / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.textBaseline = 'middle';
    ctx.fillText('node', 0, 0);
    ctx.restore();
  }

  colourBar(ctx, m, pw, ph, vlo, vhi) {
    const x = m.l + pw + 14, bw = 14;
    for (let y = 0; y < ph; y++) {
      const [r, g, b] = viridis(1 - y / Math.max(1, ph - 1));
      ctx.fillStyle = `rgb(${r | 0},${g | 0},${b | 0})`;
      ctx.fillRect(x, m.t + y, bw, 1);
    }
    ctx.font = '12px system-ui, sans-serif';
    ctx.fillStyle = getComputedStyle(document.documentElement).getPropertyValue('--ink-soft').trim() || '#555';
    ctx.textAlign = 'left';
    ctx.textBaseline = 'top';
    ctx.fillText(+vhi.toPrecision(3) + '', x + bw + 4, m.t);
    ctx.textBaseline = 'bottom';
    ctx.fillText(+vlo.toPrecision(3) + '', x + bw + 4, m.t + ph);
    ctx.textBaseline = 'middle';
    ctx.fillText('v', x + bw + 4, m.t + ph / 2);
  }
}

// The three network plots and their container; one per page, reused by every network run.
export class NetworkView {
  // contact: web/contact.js's ContactPlots (a run with contact elements gets its run and two more plots)
  constructor(contact = null) {
    this.box = $('network-plots');
    this.contact = contact;
    this.spaceTime = new SpaceTime($('plot-spacetime'));
    const timeAxis = { col: 't', label: 't', monotone: true, range: () => [0, this.spaceTime.tEnd] };
    this.timeAxis = timeAxis;
    this.px = new Plot($('plot-nodes-x'), { x: timeAxis, y: { label: 'x\u1d62' }, series: [] });
    this.pv = new Plot($('plot-nodes-v'), { x: timeAxis, y: { label: 'v\u1d62' }, series: [] });
  }

  // A new run from its meta line (and the request sent, which says which elements are contacts): the
  // curves' series and legend, the empty pictures.
  start(meta, spec = null) {
    const run = (this.contact && this.contact.runFor(meta, spec)) || new NetworkRun(meta);
    this.px.opts.markers = null;
    this.withContacts = !!run.contacts;
    if (run.contacts) this.contact.start(run, this.px, this.timeAxis);
    const series = (p) => run.curves.map((j, i) => ({ col: p + j, color: PALETTE[i % PALETTE.length] }));
    this.px.opts.series = series('x');
    this.pv.opts.series = series('v');
    this.spaceTime.run = run;
    this.spaceTime.tEnd = meta.t_end;
    for (const id of ['legend-nodes-x', 'legend-nodes-v']) // DOM, not markup: the CSP refuses inline styles
      $(id).replaceChildren(...run.curves.map((j, i) => {
        const span = document.createElement('span'), sw = document.createElement('i');
        sw.className = 'sw';
        sw.style.color = PALETTE[i % PALETTE.length];
        span.append(sw, `node ${run.nodes[j]}`);
        return span;
      }));
    $('spacetime-note').textContent = `${run.nodes.length} node${run.nodes.length === 1 ? '' : 's'} \u00d7 t, coloured by velocity`;
    this.box.dataset.nodes = run.nodes.length;
    this.box.dataset.curves = run.curves.length;
    return run;
  }

  // Shows the network plots (and hides the one-mass ones) or the other way round.
  show(on) {
    this.box.hidden = !on;
    $('plots-one').hidden = on;
    if (this.contact) this.contact.show(on && this.withContacts);
    // one node with contacts (a ball, an impact oscillator): its x(t), v(t) and phase portrait say it all
    $('plot-spacetime').closest('figure').hidden = on && this.withContacts && this.spaceTime.run?.nodes.length === 1;
  }

  draw(run) {
    for (const p of [this.px, this.pv]) { p.setTable(run ? run.table : null); p.draw(); }
    if (this.withContacts) this.contact.draw(run);
    this.spaceTime.run = run;
    this.spaceTime.draw();
  }
}
