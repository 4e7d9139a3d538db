// web/modes.js - the modes tab: a network's natural frequencies as bars, its mass-normalized mode shapes drawn
// over the node index, and the receptance of one node to a harmonic force at another on log-log axes with its
// resonances and antiresonances marked (POST v1/modes and v1/response, docs/modes.md). Plain canvas, as the
// rest of the page; the panel's dataset says what was drawn (data-modes, data-resonances, data-points).

const COLOURS = ['#1f6feb', '#d1242f', '#1a7f37', '#8250df', '#bf8700', '#0a7e8c'];

function setup(canvas) {
  const dpr = window.devicePixelRatio || 1, w = canvas.clientWidth, h = canvas.clientHeight;
  canvas.width = Math.round(w * dpr);
  canvas.height = Math.round(h * dpr);
  const g = canvas.getContext('2d');
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, w, h);
  g.font = '11px system-ui, sans-serif';
  return { g, w, h, pad: { l: 48, r: 12, t: 20, b: 24 } };
}

function frame(c, title, xlabel) {
  const { g, w, h, pad } = c;
  g.strokeStyle = '#8c959f';
  g.strokeRect(pad.l, pad.t, w - pad.l - pad.r, h - pad.t - pad.b);
  g.fillStyle = '#57606a';
  g.fillText(title, pad.l, 13);
  g.fillText(xlabel, w - pad.r - g.measureText(xlabel).width, h - 6);
}

// Bars of the frequencies (rad/s), one per mode, in the mode's colour.
function drawBars(canvas, modes) {
  const c = setup(canvas), { g, w, h, pad } = c;
  frame(c, 'natural frequencies \u03c9 (rad/s)', 'mode');
  const top = Math.max(...modes.map((m) => m.omega), 1e-12), bw = (w - pad.l - pad.r) / Math.max(modes.length, 1);
  modes.forEach((m, i) => {
    const y = pad.t + (h - pad.t - pad.b) * (1 - m.omega / top);
    g.fillStyle = COLOURS[i % COLOURS.length];
    g.fillRect(pad.l + i * bw + bw * 0.2, y, bw * 0.6, h - pad.b - y);
    g.fillStyle = '#24292f';
    g.fillText(m.omega.toPrecision(4), pad.l + i * bw + bw * 0.2, Math.max(y - 3, pad.t + 10));
  });
  canvas.dataset.points = String(modes.length);
}

// The shapes: node index on x, the normalized amplitude on y, one polyline per mode.
function drawShapes(canvas, modes) {
  const c = setup(canvas), { g, w, h, pad } = c;
  frame(c, 'mode shapes (mass-normalized)', 'node');
  const n = modes.length ? modes[0].shape.length : 0;
  const top = Math.max(...modes.flatMap((m) => m.shape.map(Math.abs)), 1e-12);
  const X = (j) => pad.l + (w - pad.l - pad.r) * (n > 1 ? j / (n - 1) : 0.5);
  const Y = (a) => pad.t + (h - pad.t - pad.b) * (0.5 - 0.45 * a / top);
  g.strokeStyle = '#d0d7de';
  g.beginPath(); g.moveTo(pad.l, Y(0)); g.lineTo(w - pad.r, Y(0)); g.stroke();
  let points = 0;
  modes.forEach((m, i) => {
    g.strokeStyle = g.fillStyle = COLOURS[i % COLOURS.length];
    g.lineWidth = 2;
    g.beginPath();
    m.shape.forEach((a, j) => (j ? g.lineTo(X(j), Y(a)) : g.moveTo(X(j), Y(a))));
    g.stroke();
    m.shape.forEach((a, j) => { g.fillRect(X(j) - 2.5, Y(a) - 2.5, 5, 5); points++; });
  });
  g.lineWidth = 1;
  canvas.dataset.points = String(points);
}

// |H(ω)| on log-log axes, the resonances (red) and antiresonances (blue) as vertical marks.
function drawResponse(canvas, resp) {
  const c = setup(canvas), { g, w, h, pad } = c;
  frame(c, `|H(\u03c9)|: node ${resp.response_node} to a force at node ${resp.force_node}`, '\u03c9 (rad/s, log)');
  const rows = resp.rows.filter((r) => r.omega > 0 && r.magnitude > 0);
  if (rows.length < 2) { canvas.dataset.points = '0'; return; }
  const lx = rows.map((r) => Math.log10(r.omega)), ly = rows.map((r) => Math.log10(r.magnitude));
  const x0 = Math.min(...lx), x1 = Math.max(...lx), y0 = Math.min(...ly), y1 = Math.max(...ly);
  const X = (v) => pad.l + (w - pad.l - pad.r) * (v - x0) / (x1 - x0 || 1);
  const Y = (v) => pad.t + (h - pad.t - pad.b) * (1 - (v - y0) / (y1 - y0 || 1));
  const mark = (omega, colour) => {
    if (!(omega > 0)) return;
    const x = X(Math.log10(omega));
    if (x < pad.l || x > w - pad.r) return;
    g.strokeStyle = colour;
    g.setLineDash([4, 3]);
    g.beginPath(); g.moveTo(x, pad.t); g.lineTo(x, h - pad.b); g.stroke();
    g.setLineDash([]);
  };
  (resp.resonances || []).forEach((r) => mark(r.omega, '#d1242f'));
  (resp.antiresonances || []).forEach((r) => mark(r.omega, '#1f6feb'));
  g.strokeStyle = '#24292f';
  g.lineWidth = 2;
  g.beginPath();
  rows.forEach((r, i) => (i ? g.lineTo(X(lx[i]), Y(ly[i])) : g.moveTo(X(lx[i]), Y(ly[i]))));
  g.stroke();
  g.lineWidth = 1;
  g.fillStyle = '#57606a';
  g.fillText(`10^${y1.toFixed(1)}`, 4, pad.t + 10);
  g.fillText(`10^${y0.toFixed(1)}`, 4, h - pad.b);
  canvas.dataset.points = String(rows.length);
}

// Runs a modes request: v1/modes always, v1/response when the document names force_node and response_node.
// post(route) returns a fetch promise; the answers are returned, the drawing done into the panel's canvases.
export async function runModes(post, text) {
  let doc = {};
  try { doc = JSON.parse(text); } catch { /* the daemon says where */ }
  const wantsResponse = doc && doc.force_node !== undefined && doc.response_node !== undefined;
  const [mr, rr] = await Promise.all([post('v1/modes'), wantsResponse ? post('v1/response') : null]);
  return { mr, rr };
}

export function renderModes(modes, resp) {
  const panel = document.getElementById('panel-modes');
  drawBars(document.getElementById('modes-bars'), modes.modes);
  drawShapes(document.getElementById('modes-shapes'), modes.modes);
  const rc = document.getElementById('modes-response');
  rc.parentElement.hidden = !resp;
  if (resp) drawResponse(rc, resp);
  panel.dataset.modes = String(modes.modes.length);
  panel.dataset.resonances = resp ? String((resp.resonances || []).length) : '';
  panel.dataset.antiresonances = resp ? String((resp.antiresonances || []).length) : '';
  const left = (modes.left_out || []).length;
  document.getElementById('modes-info').textContent =
    `${modes.modes.length} modes of ${modes.nodes} nodes` + (left ? `; ${left} set-valued element(s) left out` : '') +
    (modes.damped ? '; damped eigenvalues computed' : '');
}
