// web/right_hand.js - the page's view of a right-hand friction run (docs/right-hand.md): a model with a
// `kind` streams rows of q, qd, qdd, N, mode and margin arrays named by its meta line's `columns`. Kept apart
// from app.js as network.js is: app.js hands the meta line to start(), each sample to push(), each event to
// event(), the error to stop(), and asks draw() to paint. Two plots against t: the coordinates q (with the
// located events) and the normal reactions N; where a Painlevé paradox (or the rod leaving or reaching the
// floor) stopped the run, the rest of [0, t_end] is shaded from the stop on both.
//
// A stop is either a failure (a paradox: the friction law does not decide the motion) or the end the model
// is built to reach: Painlevé's rod with mu < 4/3 meets no paradox anywhere (Matrosov & Finogenko's
// Theorem 4.1, the meta line's check "(2.3) for every state"), so its right-hand solution goes on until it
// leaves the set the model describes (end A on the floor, 0 < theta < pi): the rod reaches the floor (an
// impact) or lifts off. designedEnd() tells a designed end from a failure by the meta line (model, mu) and
// the error line's status and title, never by the words of its detail (shown as the daemon wrote it).
//
// For tests, #rh-plots carries data-stop (the stop time, '' if none) and each canvas data-points.

import { Table, Plot } from './plot.js';

const $ = (id) => document.getElementById(id);
const MAX_ROWS = 2e6;

// The error line's title of a run stopped by its model (docs/http.md: status 422, a step not solved).
const STOPPED = { status: 422, title: 'a step could not be solved' };
// The uniform rod's bound on mu below which (2.3) holds for every state (Theorem 4.1): min over theta of
// (1 + 3 cos^2)/(3 sin cos), at tan theta = 2.
const ROD_MU = 4 / 3;

// The designed end of a run whose stream ended with the error line `err`, or null when the stop is a
// failure: {kind: 'contact', title, text} for Painlevé's rod leaving the floor's set without a paradox possible.
export function designedEnd(meta, err) {
  if (!meta || !err || err.status !== STOPPED.status || err.title !== STOPPED.title) return null;
  if (meta.model === 'painleve-rod' && meta.parameters && meta.parameters.mu < ROD_MU)
    return { kind: 'contact', title: 'Ended at contact \u2014 the end this model is built for',
      text: 'With \u03bc < 4/3 the rod meets no paradox (Matrosov & Finogenko 1995, Theorem 4.1): it slides until it reaches ' +
        'the floor or lifts off, an impact or a flight this model does not follow. The plots are shaded after it.' };
  return null;
}

export class RightHandRun {
  constructor(meta) {
    this.qNames = meta.columns.q;
    this.nNames = meta.columns.N;
    this.table = new Table(['t', 'q0', 'q1', ...this.nNames.map((_, j) => 'N' + j)]);
    this.events = [];
    this.stopAt = null;
    this.row = {};
  }

  push(o) {
    if (this.table.n >= MAX_ROWS) return;
    const r = this.row;
    r.t = o.t; r.q0 = o.q[0]; r.q1 = o.q[1];
    for (let j = 0; j < this.nNames.length; j++) r['N' + j] = o.N[j];
    this.table.push(r);
  }

  event(o) { this.events.push(o); }

  // The stop's time from the record ("... at t=<time>, ..."), else the last sample's.
  stop(err, lastT) {
    const m = /\bat t=([-+0-9.eE]+)/.exec((err && err.detail) || '');
    this.stopAt = m ? +m[1] : lastT;
  }
}

export class RightHandView {
  constructor() {
    this.box = $('rh-plots');
    this.run = null;
    this.tEnd = 1;
    const timeAxis = { col: 't', label: 't', monotone: true, range: () => [0, this.tEnd] };
    const bands = () => (this.run && this.run.stopAt !== null ? [[this.run.stopAt, this.tEnd]] : []);
    this.pq = new Plot($('plot-rh-q'), { x: timeAxis, y: { label: 'q' }, bands,
      series: [{ col: 'q0', color: '--c-x' }, { col: 'q1', color: '--c-v' }],
      markers: () => (this.run ? this.run.events.map((e) => ({ x: e.t, y: e.u, kind: e.kind })) : []) });
    this.pn = new Plot($('plot-rh-n'), { x: timeAxis, y: { label: 'N' }, bands, series: [] });
  }

  start(meta) {
    const run = new RightHandRun(meta);
    this.run = run;
    this.tEnd = meta.t_end;
    this.pn.opts.series = run.nNames.map((_, j) => ({ col: 'N' + j, color: j ? '--c-Fd' : '--c-Fs' }));
    $('rh-q-legend').textContent = `${run.qNames[0]} (blue), ${run.qNames[1]} (orange)`;
    $('rh-n-legend').textContent = run.nNames.length > 1 ? `${run.nNames[0]} (green), |${run.nNames[1]}| (magenta)`
      : `${run.nNames[0]} (green)`;
    this.box.dataset.stop = '';
    return run;
  }

  show(on) { this.box.hidden = !on; }

  draw(run) {
    this.run = run;
    this.box.dataset.stop = run && run.stopAt !== null ? String(run.stopAt) : '';
    for (const p of [this.pq, this.pn]) { p.setTable(run ? run.table : null); p.draw(); }
  }
}
