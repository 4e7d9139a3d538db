// web/lcs.js - the page's view of a linear complementarity system run (docs/lcs.md): a model with `lcs`
// streams rows of arrays x (n states), u and w (m components each), 0 <= u_j ⊥ w_j >= 0 or an interval
// law. The rows carry no names, so the preset says what each column is (its `columns`: [symbol, meaning]
// per x, u and w component, e.g. x0 = q charge, u0 = -v_D); an edited request keeps its preset's names
// while it has as many states and components, else the columns are called x0, u0, w0. Kept apart from
// app.js as network.js and right_hand.js are: start() with the meta line, push() each sample, draw().
// Three plots: the states against t, each complementarity pair against t (u_j solid, w_j dashed in
// component j's colour: where one leaves zero the other is zero), and the phase portrait x1 against x0.
//
// For tests, #lcs-plots carries data-states, data-components, data-named ("true" when the preset's names
// are used) and data-finite ("false" once a non-finite number arrived); each canvas data-points and
// data-yrange (web/plot.js).

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
    this.puw.opts.series = u.flatMap((_, j) => [{ col: 'u' + j, color: colour(j) }, { col: 'w' + j, color: colour(j), dash: [6, 4] }]);
    this.puw.opts.y.label = run.m === 1 ? `${u[0][0]}, ${w[0][0]}` : 'u, w';
    const two = run.n >= 2;
    $('lcs-phase-figure').hidden = !two;
    this.pphase.opts.series = two ? [{ col: 'x1', color: colour(0) }] : [];
    if (two) { this.pphase.opts.x.label = x[0][0]; this.pphase.opts.y.label = x[1][0]; }
    $('lcs-x-legend').replaceChildren(...x.map((s, j) => entry(colour(j), false, said(s, 'x' + j))));
    $('lcs-uw-legend').replaceChildren(...u.flatMap((s, j) => [entry(colour(j), false, said(s, 'u' + j)),
      entry(colour(j), true, said(w[j], 'w' + j))]));
    $('lcs-phase-legend').textContent = two ? `${x[1][0]} against ${x[0][0]}` : '';
    Object.assign(this.box.dataset, { states: run.n, components: run.m, named: String(run.names.named), finite: 'true' });
    return run;
  }

  show(on) { this.box.hidden = !on; }

  draw(run) {
    if (run) this.box.dataset.finite = String(run.finite);
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
