// web/plot.js - line plots on a plain <canvas>, no library: nice ticks, labelled axes, grid, shaded
// intervals (stick phases), event markers (canvas.dataset.markers counts those drawn by kind). A Table holds the samples as growable columns; a Plot draws
// some of its columns against another and records how many points it drew (canvas.dataset.points).

export class Table {
  constructor(names) {
    this.names = names;
    this.n = 0;
    this.cap = 4096;
    this.col = {};
    this.min = {};
    this.max = {};
    for (const k of names) {
      this.col[k] = new Float64Array(this.cap);
      this.min[k] = Infinity;
      this.max[k] = -Infinity;
    }
  }

  push(row) {
    if (this.n === this.cap) {
      this.cap *= 2;
      for (const k of this.names) {
        const a = new Float64Array(this.cap);
        a.set(this.col[k]);
        this.col[k] = a;
      }
    }
    for (const k of this.names) {
      const v = row[k];
      this.col[k][this.n] = v;
      if (v < this.min[k]) this.min[k] = v;
      if (v > this.max[k]) this.max[k] = v;
    }
    this.n++;
  }
}

// Ticks at 1, 2 or 5 times a power of ten, about `count` of them over [lo, hi].
export function niceStep(lo, hi, count) {
  const raw = (hi - lo) / Math.max(1, count);
  const mag = 10 ** Math.floor(Math.log10(raw));
  const r = raw / mag;
  return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * mag;
}

export function tickLabel(v, step) {
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-3) return v.toExponential(Math.max(0, Math.min(6, Math.round(Math.log10(a / step)))));
  return v.toFixed(Math.max(0, Math.min(10, -Math.floor(Math.log10(step) + 1e-9))));
}

// [lo, hi] widened to whole ticks, never empty.
function niceRange(lo, hi, count) {
  if (!Number.isFinite(lo) || !Number.isFinite(hi)) return [0, 1];
  if (hi - lo < 1e-12 * Math.max(1, Math.abs(lo), Math.abs(hi))) {
    const d = Math.abs(lo) > 1e-9 ? Math.abs(lo) * 0.1 : 1;
    lo -= d;
    hi += d;
  }
  const pad = 0.03 * (hi - lo); // data never sits on the frame
  lo -= pad;
  hi += pad;
  const step = niceStep(lo, hi, count);
  return [Math.floor(lo / step + 1e-9) * step, Math.ceil(hi / step - 1e-9) * step];
}

// A colour: a CSS variable of the page (--name) or a colour as it is (the network view's per-node curves).
const css = (name) => (name.startsWith('--') ? getComputedStyle(document.documentElement).getPropertyValue(name).trim() || '#000' : name);

// opts: { x: {col, label, range?: () => [lo, hi]}, y: {label}, series: [{col, color, dash?, dashOffset?}],
//         bands?: () => [[x0, x1], ...], markers?: () => [{x, y, kind}],
//         stems?: {label, color, values: () => [{x, p}]} }
// Stems are impulses (a force's Dirac mass at x, of weight p >= 0 pushing the contact's ends apart, the
// side of the negative forces): vertical lines down from the zero line with a dot at the tip, their length
// on a scale of their own, the right axis (labelled with `label`); canvas.dataset.stems counts them.
export class Plot {
  constructor(canvas, opts) {
    this.canvas = canvas;
    this.opts = opts;
    this.table = null;
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  setTable(table) {
    this.table = table;
  }

  draw() {
    const { canvas, opts } = this;
    const dpr = window.devicePixelRatio || 1;
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (w === 0 || h === 0) return;
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr);
      canvas.height = Math.round(h * dpr);
    }
    const ctx = canvas.getContext('2d');
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, w, h);
    const t = this.table;
    const n = t ? t.n : 0;
    const stems = opts.stems ? opts.stems.values() : [];
    const m = { l: 62, r: opts.stems ? 58 : 14, t: 10, b: 42 };
    const pw = w - m.l - m.r, ph = h - m.t - m.b;

    // ranges
    let [xlo, xhi] = opts.x.range ? opts.x.range() : [t ? t.min[opts.x.col] : NaN, t ? t.max[opts.x.col] : NaN];
    let ylo = Infinity, yhi = -Infinity;
    if (t) for (const s of opts.series) { ylo = Math.min(ylo, t.min[s.col]); yhi = Math.max(yhi, t.max[s.col]); }
    const [dlo, dhi] = [ylo, yhi];
    if (stems.length) { // room below the zero line for the stems
      ylo = Math.min(ylo, 0, -(Math.max(Math.abs(yhi), Math.abs(ylo)) || 1)); // a force that is 0 throughout: [-1, 0]
      yhi = Math.max(yhi, 0);
    }
    const xticks = Math.max(2, Math.round(pw / 90)), yticks = Math.max(2, Math.round(ph / 48));
    if (!opts.x.range) [xlo, xhi] = niceRange(xlo, xhi, xticks);
    [ylo, yhi] = niceRange(ylo, yhi, yticks);
    const X = (v) => m.l + ((v - xlo) / (xhi - xlo)) * pw;
    const Y = (v) => m.t + ph - ((v - ylo) / (yhi - ylo)) * ph;

    // grid, ticks and labels
    ctx.font = '12px system-ui, sans-serif';
    ctx.lineWidth = 1;
    ctx.strokeStyle = css('--grid');
    ctx.fillStyle = css('--ink-soft');
    const xs = niceStep(xlo, xhi, xticks), ys = niceStep(ylo, yhi, yticks);
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    for (let v = Math.ceil(xlo / xs - 1e-9) * xs; v <= xhi + xs * 1e-9; v += xs) {
      const px = Math.round(X(v)) + 0.5;
      ctx.beginPath(); ctx.moveTo(px, m.t); ctx.lineTo(px, m.t + ph); ctx.stroke();
      ctx.fillText(tickLabel(Math.abs(v) < xs * 1e-9 ? 0 : v, xs), px, m.t + ph + 5);
    }
    ctx.textAlign = 'right';
    ctx.textBaseline = 'middle';
    for (let v = Math.ceil(ylo / ys - 1e-9) * ys; v <= yhi + ys * 1e-9; v += ys) {
      const py = Math.round(Y(v)) + 0.5;
      ctx.beginPath(); ctx.moveTo(m.l, py); ctx.lineTo(m.l + pw, py); ctx.stroke();
      ctx.fillText(tickLabel(Math.abs(v) < ys * 1e-9 ? 0 : v, ys), m.l - 6, py);
    }
    ctx.fillStyle = css('--ink');
    ctx.font = 'italic 13px system-ui, sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'bottom';
    ctx.fillText(opts.x.label, m.l + pw / 2, h - 4);
    ctx.save();
    ctx.translate(14, m.t + ph / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.textBaseline = 'middle';
    ctx.fillText(opts.y.label, 0, 0);
    ctx.restore();

    // data, clipped to the plot area
    ctx.save();
    ctx.beginPath();
    ctx.rect(m.l, m.t, pw, ph);
    ctx.clip();
    if (opts.bands) {
      ctx.fillStyle = css('--stick');
      for (const [a, b] of opts.bands()) {
        const x0 = Math.max(m.l, X(a)), x1 = Math.min(m.l + pw, X(b));
        if (x1 > x0 - 1) ctx.fillRect(x0, m.t, Math.max(1, x1 - x0), ph);
      }
    }
    if (ylo < 0 && yhi > 0) { // the zero line
      ctx.strokeStyle = css('--axis-zero');
      ctx.beginPath(); ctx.moveTo(m.l, Math.round(Y(0)) + 0.5); ctx.lineTo(m.l + pw, Math.round(Y(0)) + 0.5); ctx.stroke();
    }
    ctx.lineWidth = 1.6;
    ctx.lineJoin = 'round';
    for (const s of opts.series) {
      ctx.strokeStyle = css(s.color);
      ctx.setLineDash(s.dash || []);
      ctx.lineDashOffset = s.dashOffset || 0;
      if (t) line(ctx, t.col[opts.x.col], t.col[s.col], n, X, Y, opts.x.monotone, pw * dpr);
    }
    ctx.setLineDash([]);
    ctx.lineDashOffset = 0;
    const drawn = {};
    if (opts.markers) { // breakaways first: a stick at the same point stays visible inside its triangle
      const mks = opts.markers();
      for (const kind of MARKER_KINDS) for (const mk of mks) if (mk.kind === kind) { marker(ctx, X(mk.x), Y(mk.y), kind); drawn[kind] = (drawn[kind] || 0) + 1; }
    }
    let stemScale = null;
    if (stems.length) {
      const top = Math.max(...stems.map((st) => st.p), 1e-300), y0 = Y(0), room = m.t + ph - y0;
      stemScale = { top: top / 0.92, y0, room }; // the largest stem reaches 92% of the way down
      const P = (p) => y0 + (p / stemScale.top) * room;
      ctx.strokeStyle = ctx.fillStyle = css(opts.stems.color);
      ctx.lineWidth = 2;
      for (const st of stems) {
        const px = Math.round(X(st.x)) + 0.5;
        ctx.beginPath(); ctx.moveTo(px, y0); ctx.lineTo(px, P(st.p)); ctx.stroke();
        ctx.beginPath(); ctx.arc(px, P(st.p), 3, 0, 2 * Math.PI); ctx.fill();
      }
    }
    ctx.restore();
    if (stemScale) { // the stems' own axis, on the right, in their colour
      const { top, y0, room } = stemScale, s = niceStep(0, top, Math.max(2, Math.round(room / 40)));
      ctx.font = '12px system-ui, sans-serif';
      ctx.fillStyle = ctx.strokeStyle = css(opts.stems.color);
      ctx.lineWidth = 1;
      ctx.textAlign = 'left';
      ctx.textBaseline = 'middle';
      for (let v = 0; v <= top + s * 1e-9; v += s) {
        const py = Math.round(y0 + (v / top) * room) + 0.5;
        ctx.beginPath(); ctx.moveTo(m.l + pw, py); ctx.lineTo(m.l + pw + 4, py); ctx.stroke();
        ctx.fillText(tickLabel(v, s), m.l + pw + 6, py);
      }
      ctx.save();
      ctx.translate(w - 8, y0 + room / 2);
      ctx.rotate(-Math.PI / 2);
      ctx.font = 'italic 13px system-ui, sans-serif';
      ctx.textAlign = 'center';
      ctx.fillText(opts.stems.label, 0, 0);
      ctx.restore();
    }
    canvas.dataset.stems = String(stems.length);
    ctx.strokeStyle = css('--frame');
    ctx.lineWidth = 1;
    ctx.strokeRect(m.l + 0.5, m.t + 0.5, pw - 1, ph - 1);
    canvas.dataset.points = String(n);
    canvas.dataset.markers = Object.entries(drawn).map(([k, c]) => `${k}:${c}`).join(','); // e.g. "yield:16,unload:15"
    canvas.dataset.yrange = t && opts.series.length ? `${dlo},${dhi}` : ''; // the data's, before the ticks widen it
  }
}

// A polyline through n points. Along a monotone x with many more points than pixels, each pixel column
// is drawn as its first, lowest, highest and last value (the picture is the same, the work bounded).
function line(ctx, xs, ys, n, X, Y, monotone, widthPx) {
  if (n === 0) return;
  ctx.beginPath();
  if (monotone && n > 2 * widthPx) {
    let col = null, first = 0, lo = 0, hi = 0, last = 0, started = false;
    const flush = () => {
      if (col === null) return;
      if (started) ctx.lineTo(col, first); else { ctx.moveTo(col, first); started = true; }
      if (lo !== hi) { ctx.lineTo(col, lo); ctx.lineTo(col, hi); }
      ctx.lineTo(col, last);
    };
    for (let i = 0; i < n; i++) {
      const px = Math.round(X(xs[i]) * 2) / 2, py = Y(ys[i]);
      if (px !== col) { flush(); col = px; first = lo = hi = last = py; }
      else { if (py < lo) lo = py; if (py > hi) hi = py; last = py; }
    }
    flush();
  } else {
    let lx = X(xs[0]), ly = Y(ys[0]);
    ctx.moveTo(lx, ly);
    for (let i = 1; i < n; i++) {
      const px = X(xs[i]), py = Y(ys[i]);
      if (Math.abs(px - lx) < 0.25 && Math.abs(py - ly) < 0.25 && i < n - 1) continue;
      ctx.lineTo(px, py);
      lx = px;
      ly = py;
    }
    if (n === 1) ctx.lineTo(lx + 0.01, ly);
  }
  ctx.stroke();
}

// The event kinds drawn as markers, in drawing order (docs/http.md, docs/contact.md; yield and unload are an
// elastoplastic spring's: its slider starts sliding, and stops).
const MARKER_KINDS = ['slip', 'stick', 'impact', 'yield', 'unload'];

// stick (slip -> stick): a filled dark circle; slip (breakaway): an open triangle; impact: a filled diamond;
// yield: a filled square; unload: an open square.
export function marker(ctx, x, y, kind) {
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  if (kind === 'yield' || kind === 'unload') {
    ctx.rect(x - 4.5, y - 4.5, 9, 9);
    ctx.fillStyle = kind === 'yield' ? css('--ev-yield') : '#fff';
    ctx.strokeStyle = kind === 'yield' ? '#fff' : css('--ev-yield');
    ctx.fill();
    ctx.stroke();
    if (kind === 'yield') { // a white edge alone would vanish on the white background
      ctx.strokeStyle = css('--ev-yield');
      ctx.lineWidth = 1;
      ctx.strokeRect(x - 5.5, y - 5.5, 11, 11);
    }
  } else if (kind === 'impact') {
    ctx.moveTo(x, y - 6); ctx.lineTo(x + 5, y); ctx.lineTo(x, y + 6); ctx.lineTo(x - 5, y); ctx.closePath();
    ctx.fillStyle = css('--ev-impact');
    ctx.strokeStyle = '#fff';
    ctx.fill();
    ctx.stroke();
  } else if (kind === 'stick') {
    ctx.arc(x, y, 4, 0, 2 * Math.PI);
    ctx.fillStyle = css('--ev-stick');
    ctx.strokeStyle = '#fff';
    ctx.fill();
    ctx.stroke();
  } else {
    ctx.moveTo(x, y - 8); ctx.lineTo(x + 7, y + 5); ctx.lineTo(x - 7, y + 5); ctx.closePath();
    ctx.fillStyle = '#fff';
    ctx.strokeStyle = css('--ev-slip');
    ctx.fill();
    ctx.stroke();
  }
}
