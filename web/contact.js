// web/contact.js - contacts and impacts on a network run (docs/contact.md): an element with a "contact"
// keeps its elongation u = x_b - x_a >= distance, rigidly (Newton's impact law, restitution e) or through a
// compliance; the rows carry each written element's contact force Fn, the stream an "impact" event per
// impact (t, u, the rate du before and du_after after, the impulse). The meta line does not say which
// elements are contacts, so the request sent says it (contactsOf). network.js keeps drawing x_i(t), v_i(t)
// and the space-time picture; this adds what a contact run needs: impact markers on x_i(t), the phase
// portrait v against x of the node the first contact holds, and the contact forces against t.
//
// An impact is a jump of v at one instant, so between two decimated samples the phase portrait would draw
// a slanted chord where the motion has a vertical jump. When the run writes one node and the contact joins
// it to the ground, the impact's own state is exact (x = ±u, v = ±du before, ±du_after after; the sign is
// the node's side of the element), so two rows are added to the table at the impact's t: the curves go
// through the stop and jump there. With more nodes the others' states at that instant are not in the
// stream, so no rows are added (markers only).
//
// For tests, #network-plots carries data-contacts (contact elements written), data-impacts (impact events
// received), data-impact-rows (rows added at impacts) and data-finite ("false" once a non-finite number
// arrived); the phase and force canvases data-points and data-yrange (web/plot.js), the force canvas
// data-stems (the impulses drawn as stems at their impacts' times: a rigid contact's Fn is 0 between them).

import { Plot } from './plot.js';
import { NetworkRun } from './network.js';

const $ = (id) => document.getElementById(id);
const PALETTE = ['#0072b2', '#d55e00', '#009e73', '#cc79a7', '#e69f00', '#56b4e9', '#7a5cc4', '#000000'];

// The written elements of the request that carry a contact: {element, col (its place among the written
// elements, the Fn column), between, distance, rigid}. None when the request cannot be read. A one-mass
// document with a contact runs as the network of one node whose element 0 is ["ground", 0] (docs/contact.md).
export function contactsOf(spec, meta) {
  const model = (spec && spec.model) || {};
  const elements = Array.isArray(model.elements) ? model.elements
    : model.contact ? [{ between: ['ground', 0], contact: model.contact }] : [];
  const written = meta.columns.elements;
  return written.flatMap((e, col) => {
    const el = elements[e];
    if (!el || !el.contact || typeof el.contact !== 'object') return [];
    return [{ element: e, col, between: el.between, distance: el.contact.distance, rigid: !('compliance' in el.contact) }];
  });
}

// The node a contact holds against the ground, with the sign of its x in u (+1 when the node is the
// element's b end: u = x_b), or null for a contact between two nodes.
function groundEnd(c) {
  const [a, b] = c.between || [];
  if (a === 'ground' && b !== 'ground') return { node: b, sign: 1 };
  if (b === 'ground' && a !== 'ground') return { node: a, sign: -1 };
  return null;
}

export class ContactRun extends NetworkRun {
  constructor(meta, contacts) {
    super(meta, contacts.map((_, i) => 'Fn' + i));
    this.contacts = contacts;
    this.impacts = []; // {t, x, v, element}: where each impact is marked (x, v after it), x null between nodes
    this.impactRows = 0;
    this.finite = true;
    const held = contacts.map(groundEnd).find((g) => g && this.nodes.includes(g.node));
    this.phaseCol = held ? this.nodes.indexOf(held.node) : 0; // the phase portrait's node column
  }

  push(o) {
    const fn = o.Fn || [];
    this.contacts.forEach((c, i) => { this.row['Fn' + i] = fn[c.col]; });
    for (const g of ['x', 'v', 'Fn']) for (const v of o[g] || []) if (!Number.isFinite(v)) this.finite = false;
    return super.push(o);
  }

  // An event of the stream: an impact is marked and, where its state is exact (see the top), tabled.
  event(o) {
    if (o.kind !== 'impact') return;
    const c = this.contacts.find((k) => k.element === o.element), g = c && groundEnd(c);
    const j = g ? this.nodes.indexOf(g.node) : -1;
    if (j < 0) { this.impacts.push({ t: o.t, x: null, v: null, element: o.element, impulse: o.impulse }); return; }
    const x = g.sign * o.u, v = g.sign * o.du_after;
    this.impacts.push({ t: o.t, x, v, j, element: o.element, impulse: o.impulse });
    if (this.nodes.length !== 1 || this.table.n === 0 || this.table.n + 2 > this.maxRows) return;
    this.row.t = o.t;
    this.row['x' + j] = x;
    for (const rate of [o.du, o.du_after]) { this.row['v' + j] = g.sign * rate; this.table.push(this.row); }
    this.impactRows += 2;
  }
}

// The phase portrait and the contact-force plot, shown with the network plots for a run with contacts.
// network.js holds one (it never imports this file: ContactRun extends its NetworkRun) and asks runFor()
// for the run of each meta line, start() with its x_i(t) plot and time axis, show() and draw().
export class ContactPlots {
  constructor() {
    this.box = $('network-plots');
    this.phase = new Plot($('plot-contact-phase'), { x: { col: 'x0', label: 'x' }, y: { label: 'v' }, series: [] });
    this.fn = new Plot($('plot-contact-fn'), { x: { col: 't', label: 't' }, y: { label: 'Fn' }, series: [] });
  }

  // A ContactRun when the request has contact elements among the written ones, else null.
  runFor(meta, spec) {
    const contacts = contactsOf(spec, meta);
    return contacts.length ? new ContactRun(meta, contacts) : null;
  }

  // A new run: the phase portrait of its held node, one force curve per contact, impact markers on xPlot.
  start(run, xPlot, timeAxis) {
    this.fn.opts.x = timeAxis;
    const j = run.phaseCol, name = run.nodes[j];
    Object.assign(this.phase.opts, { x: { col: 'x' + j, label: `x${name}` }, y: { label: `v${name}` },
      series: [{ col: 'v' + j, color: PALETTE[0] }],
      markers: () => run.impacts.filter((m) => m.j === j).map((m) => ({ x: m.x, y: m.v, kind: 'impact' })) });
    this.fn.opts.series = run.contacts.map((_, i) => ({ col: 'Fn' + i, color: PALETTE[i % PALETTE.length] }));
    // a rigid contact's force is an impulse at each impact, not a finite Fn: a stem at its time (the right axis)
    this.fn.opts.stems = { label: 'impulse', color: '--ev-impact',
      values: () => run.impacts.filter((m) => Number.isFinite(m.impulse)).map((m) => ({ x: m.t, p: m.impulse })) };
    xPlot.opts.markers = () => run.impacts.filter((m) => m.x !== null).map((m) => ({ x: m.t, y: m.x, kind: 'impact' }));
    $('legend-contact-phase').textContent = `node ${name}; \u25c6 after each impact`;
    const stem = document.createElement('span'), mk = document.createElement('i');
    mk.className = 'mk stem';
    stem.append(mk, 'impulse at each impact (right axis)');
    $('legend-contact-fn').replaceChildren(...run.contacts.map((c, i) => {
      const span = document.createElement('span'), sw = document.createElement('i');
      sw.className = 'sw';
      sw.style.color = PALETTE[i % PALETTE.length]; // CSSOM, not markup: the CSP refuses inline styles
      span.append(sw, `element ${c.element} (${c.rigid ? 'rigid' : 'compliant'}, u \u2265 ${c.distance})`);
      return span;
    }), stem);
    this.dataset(run);
  }

  dataset(run) {
    Object.assign(this.box.dataset, { contacts: run ? run.contacts.length : 0, impacts: run ? run.impacts.length : 0,
      impactRows: run ? run.impactRows : 0, finite: String(!run || run.finite) });
  }

  show(on) {
    for (const id of ['contact-phase-figure', 'contact-fn-figure']) $(id).hidden = !on;
  }

  draw(run) {
    this.dataset(run);
    for (const p of [this.phase, this.fn]) { p.setTable(run ? run.table : null); p.draw(); }
  }
}
