// web/lcs.js - the page's view of a linear complementarity system run (docs/lcs.md): a model with `lcs`
// streams rows of arrays x (n states), u and w (m components each), 0 <= u_j ⊥ w_j >= 0 or an interval
// law. The rows carry no names, so the preset says what each column is (its `columns`: [symbol, meaning]
// per x, u and w component, e.g. x0 = q charge, u0 = -v_D); an edited request keeps its preset's names
// while it has as many states and components, else the columns are called x0, u0, w0. Kept apart from
// app.js as network.js and right_hand.js are: start() with the meta line, push() each sample, draw().
// Three plots: the states against t, each complementarity pair against t (u_j solid, w_j dashed in
// component j's colour: where one leaves zero the other is zero), and the phase portrait x1 against x0.
//
// Curves that coincide throughout (the bridge's currents and reverse voltages pair up in two groups of
// four) are drawn in alternating dashes, each showing its colour, and the legend says they coincide.
//
// For tests, #lcs-plots carries data-states, data-components, data-named ("true" when the preset's names
// are used), data-finite ("false" once a non-finite number arrived) and data-coincide (the coinciding
// groups, "u0=u2=w1=w3;..."); each canvas data-points and data-yrange (web/plot.js).

import { Table, Plot } from './plot.js';

const $ = (id) => document.getElementById(id);
const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);
const MAX_ROWS = 2e6;
// Okabe-Ito, colour-blind safe, one colour per state or component
const PALETTE = ['#0072b2', '#d55e00', '#009e73', '#cc79a7', '#e69f00', '#56b4e9', '#7a5cc4', '#000000'];
const colour = (j) => PALETTE[j % PALETTE.length];

// The preset's [symbol, meaning] names when they fit the run, else the bare column names.
function namesFor(meta, columns) {
  const n = meta.states, m = meta.components;
  const fits = columns && columns.x?.length === n && columns.u?.length === m && columns.w?.length === m;
  const bare = (g, k) => Array.from({ length: k }, (_, j) => [g + j, '']);
  return fits ? { named: true, x: columns.x, u: columns.u, w: columns.w }
    : { named: false, x: bare('x', n), u: bare('u', m), w: bare('w', m) };
}

// The samples of one LCS run as columns t, x0.., u0.., w0...
export class LcsRun {
  constructor(meta, columns) {
    this.n = meta.states;
    this.m = meta.components;
    this.names = namesFor(meta, columns);
    const col = (g, k) => Array.from({ length: k }, (_, j) => g + j);
    this.table = new Table(['t', ...col('x', this.n), ...col('u', this.m), ...col('w', this.m)]);
    this.finite = true;
    this.row = {};
  }

  push(o) {
    if (this.table.n >= MAX_ROWS) return;
    const r = this.row;
    r.t = o.t;
    for (const g of ['x', 'u', 'w']) for (let j = 0; j < o[g].length; j++) r[g + j] = o[g][j];
    for (const k of this.table.names) if (!Number.isFinite(r[k])) this.finite = false;
    this.table.push(r);
  }
}

// The groups (two or more) of columns equal at every row, to within 1e-9 of the columns' span, in the order
// given (each group's u columns first); a long table is compared at up to 20000 rows spread over it.
const byName = (a, b) => a[0].localeCompare(b[0]) || +a.slice(1) - +b.slice(1); // u before w, then by index
function coinciding(table, cols) {
  const n = table.n, stride = Math.max(1, Math.ceil(n / 20000)), groups = [], taken = new Set();
  const span = Math.max(1e-300, ...cols.map((c) => table.max[c] - table.min[c]));
  const same = (a, b) => {
    const A = table.col[a], B = table.col[b];
    for (let i = 0; i < n; i += stride) if (!(Math.abs(A[i] - B[i]) <= 1e-9 * span)) return false;
    return Math.abs(A[n - 1] - B[n - 1]) <= 1e-9 * span;
  };
  for (const [i, a] of cols.entries()) {
    if (taken.has(a)) continue;
    const g = [a, ...cols.slice(i + 1).filter((b) => !taken.has(b) && same(a, b))];
    if (g.length > 1) { groups.push(g.sort(byName)); g.forEach((c) => taken.add(c)); }
  }
  return groups;
}

// A legend entry: a swatch (solid or dashed) in a colour, then the text.
function entry(color, dashed, text) {
  const span = document.createElement('span'), sw = document.createElement('i');
  sw.className = dashed ? 'sw dash' : 'sw';
  sw.style.color = color; // CSSOM, not markup: the CSP refuses inline style attributes
  span.append(sw, text);
  return span;
}
const said = ([sym, meaning], col) => (sym === col ? col : `${col} = ${sym}`) + (meaning ? ` (${meaning})` : '');

export class LcsView {
  constructor() {
    this.box = $('lcs-plots');
    this.tEnd = 1;
    const timeAxis = { col: 't', label: 't', monotone: true, range: () => [0, this.tEnd] };
    this.px = new Plot($('plot-lcs-x'), { x: timeAxis, y: { label: 'x' }, series: [] });
    this.puw = new Plot($('plot-lcs-uw'), { x: timeAxis, y: { label: 'u, w' }, series: [] });
    this.pphase = new Plot($('plot-lcs-phase'), { x: { col: 'x0', label: 'x0' }, y: { label: 'x1' }, series: [] });
  }

  // A new run from its meta line and the preset's column names: series, axis labels and legends.
  start(meta, columns) {
    const run = new LcsRun(meta, columns), { x, u, w } = run.names;
    this.tEnd = meta.t_end;
    this.px.opts.series = x.map((_, j) => ({ col: 'x' + j, color: colour(j) }));
    this.px.opts.y.label = x.map((s) => s[0]).join(', ');
    this.uwSeries = u.flatMap((_, j) => [{ col: 'u' + j, color: colour(j) }, { col: 'w' + j, color: colour(j), dash: [6, 4] }]);
    this.puw.opts.series = this.uwSeries;
    this.groups = '';
    this.puw.opts.y.label = run.m === 1 ? `${u[0][0]}, ${w[0][0]}` : 'u, w';
    const two = run.n >= 2;
    $('lcs-phase-figure').hidden = !two;
    this.pphase.opts.series = two ? [{ col: 'x1', color: colour(0) }] : [];
    if (two) { this.pphase.opts.x.label = x[0][0]; this.pphase.opts.y.label = x[1][0]; }
    $('lcs-x-legend').replaceChildren(...x.map((s, j) => entry(colour(j), false, said(s, 'x' + j))));
    this.uwEntries = u.flatMap((s, j) => [entry(colour(j), false, said(s, 'u' + j)), entry(colour(j), true, said(w[j], 'w' + j))]);
    this.coincide = document.createElement('span');
    this.coincide.className = 'coincide';
    this.coincide.hidden = true;
    $('lcs-uw-legend').replaceChildren(...this.uwEntries, this.coincide);
    $('lcs-phase-legend').textContent = two ? `${x[1][0]} against ${x[0][0]}` : '';
    Object.assign(this.box.dataset, { states: run.n, components: run.m, named: String(run.names.named), finite: 'true', coincide: '' });
    return run;
  }

  show(on) { this.box.hidden = !on; }

  // Curves of the complementarity plot that coincide (the bridge's: a diode's current equals another's reverse
  // voltage throughout) would hide each other, the last drawn on top: each group of k is drawn in alternating
  // dashes, member i on every k-th dash of its own colour, and the legend says which coincide.
  separate(run) {
    const groups = coinciding(run.table, this.uwSeries.map((s) => s.col));
    const key = groups.map((g) => g.join('=')).join(';');
    if (key === this.groups) return;
    this.groups = key;
    const L = 7, member = new Map(groups.flatMap((g) => g.map((c, i) => [c, [i, g.length]])));
    this.puw.opts.series = this.uwSeries.map((s) => {
      const m = member.get(s.col);
      return m ? { ...s, dash: [L, (m[1] - 1) * L], dashOffset: -m[0] * L } : s;
    });
    this.box.dataset.coincide = key;
    this.coincide.hidden = !groups.length;
    this.coincide.textContent = groups.length ? `coincide: ${groups.map((g) => g.join(' = ')).join('; ')} (drawn in alternating dashes)` : '';
  }

  draw(run) {
    if (run) this.box.dataset.finite = String(run.finite);
    if (run && run.table.n > 1) this.separate(run);
    for (const p of [this.px, this.puw, this.pphase]) { p.setTable(run ? run.table : null); p.draw(); }
  }
}

// The meta line's account of the θ-step (an LCS run has no well-posedness report of the one-mass kind):
// D's theory and the step's matrix D + hCWB, whether it is a P-matrix (one u per step) and its µ.
export function lcsReport(meta) {
  const row = (name, part) => {
    const th = part.theory, ok = th.p_matrix;
    return `<div class="verdict ${ok ? 'ok' : 'no'}"><span class="badge">${ok ? '\u2713' : '\u2717'} ${name}: ` +
      `${ok ? 'a P-matrix' : 'not a P-matrix'}, \u00b5 = ${esc(+th.mu.toPrecision(4))}</span> <span>${esc(part.uniqueness)}</span></div>`;
  };
  return `<p class="muted">Framework LCS: the \u03b8-step solves one LCP per step with the matrix D + hCWB (docs/lcs.md).</p>` +
    row('the step\u2019s matrix D + hCWB', meta.step) + row('D', meta.D);
}
