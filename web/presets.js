// web/presets.js - the runs the page offers: the thesis' figures, the paper's two counterexamples (each
// branch), a forced oscillator, a belt-driven stick-slip, networks, circuits, contacts and impacts, and
// stability maps, and sweeps (response curves, bifurcation diagrams). kind: which tab runs it.

const linear = { law: 'linear', k: 1 };
const thesis = (x0, relaxed) => ({
  model: {
    mass: 1, spring: linear,
    damper: { law: 'coulomb', phi0: 1, ...(relaxed ? { relaxation: { kind: 'rational', a: 0.5, b: 1 } } : {}) },
  },
  initial: { x: x0, v: 0 },
  solver: { kind: 'stick-slip', variant: 'thesis', dt: 0.001, t_end: 10, Z: 100, eps: 1e-4 },
});
const counter1 = (branch) => ({
  model: { mass: 1, spring: linear, damper: { law: 'generalized-coulomb', phi0: 0.5, phi1: 1 },
    forcing: { kind: 'constant', value: 1 } },
  initial: { x: 0, v: 0 },
  solver: { kind: 'stick-slip', dt: 0.001, t_end: 10, branch },
});
const counter2 = (branch) => ({
  model: { mass: 1, spring: linear, damper: { law: 'coulomb', phi0: 1, relaxation: { kind: 'power', N: 2 } },
    forcing: { kind: 'constant', value: 1 } },
  initial: { x: 0, v: 0 },
  solver: { kind: 'stick-slip', dt: 0.001, t_end: 10, branch },
});

export const PRESETS = [];
for (const relaxed of [false, true])
  for (const x0 of [1, 2, 3, 4, 5])
    PRESETS.push({
      id: `thesis-${x0}${relaxed ? '-gamma' : ''}`,
      group: relaxed ? 'Thesis Figs. 4.2\u20134.5, with \u03b3 = 0.5 v/(1+|v|)' : 'Thesis Figs. 4.2\u20134.5, \u03b3 = 0',
      label: `x0 = ${x0}${relaxed ? ', with \u03b3' : ''}`,
      kind: 'simulate',
      note: 'm = k = \u03c6\u2080 = 1, dt = 10\u207b\u00b3, T = 10, algorithm 4.1 of the thesis (variant "thesis").' +
        (relaxed ? ' The relaxation \u03b3 = 0.5 v/(1+|v|) pumps energy back in while it slips.' :
          ' The turning points shrink by 2\u03c6\u2080/k per half swing until |x| \u2264 \u03c6\u2080/k; then it sticks.'),
      spec: thesis(x0, relaxed),
    });
for (const branch of ['rest', 'motion']) {
  PRESETS.push({
    id: `counter-gc-${branch}`, group: 'The paper\u2019s counterexamples (non-uniqueness)',
    label: `Gen. Coulomb \u03c6\u2080 0.5, \u03c6\u2081 1, F \u2261 1: ${branch}`, kind: 'simulate',
    note: 'Static threshold above the dynamic one: with F = \u03c6\u2081 from rest both x = 0 and x = (\u03c6\u2081 \u2212 \u03c6\u2080)(1 \u2212 cos t) ' +
      `solve. "branch": "${branch}" picks ${branch === 'rest' ? 'the one that stays at rest' : 'the one that moves'}.`,
    spec: counter1(branch),
  });
}
for (const branch of ['rest', 'motion']) {
  PRESETS.push({
    id: `counter-power-${branch}`, group: 'The paper\u2019s counterexamples (non-uniqueness)',
    label: `Coulomb + \u03b3 power N = 2, F \u2261 1: ${branch}`, kind: 'simulate',
    note: '\u03b3 = N|v|^(1\u22121/N) sgn v is not Lipschitz at 0: with F = \u03c6\u2080 from rest both x = 0 and a solution ' +
      `leaving rest like t^(N+1)/(N+1) solve. "branch": "${branch}".`,
    spec: counter2(branch),
  });
}
PRESETS.push({
  id: 'forced', group: 'Oscillators', label: 'Forced: Coulomb \u03c6\u2080 0.5, F = cos(t/2)', kind: 'simulate',
  note: 'A harmonic load on a Coulomb damper: it holds while |F \u2212 kx| \u2264 \u03c6\u2080, breaks away, glides, sticks again.',
  spec: {
    model: { mass: 1, spring: linear, damper: { law: 'coulomb', phi0: 0.5 },
      forcing: { kind: 'harmonic', amplitude: 1, omega: 0.5 } },
    initial: { x: 1, v: 0 },
    solver: { kind: 'stick-slip', dt: 0.001, t_end: 40, theta: 0.5 },
    output: { every: 10 },
  },
});
PRESETS.push({
  id: 'elastoplastic', group: 'Oscillators', label: 'Elastoplastic (Jenkins) spring: k 1, yield 0.5, F = 0.6 cos(0.8 t)',
  kind: 'simulate',
  note: 'A spring in series with a Coulomb slider (H\u00f6schl \u00a715): elastic while |F\u209b| < 0.5, then the slider ' +
    'slides and the offset p moves. Near resonance it yields every swing: the spring law plot draws the hysteresis ' +
    'loops, whose area is the plastic work.',
  spec: {
    model: { mass: 1, spring: { law: 'elastoplastic', k: 1, yield: 0.5 }, damper: { law: 'linear', c: 0.05 },
      forcing: { kind: 'harmonic', amplitude: 0.6, omega: 0.8 } },
    initial: { x: 0, v: 0 },
    solver: { kind: 'stick-slip', dt: 0.001, t_end: 60, theta: 0.5 },
  },
});
PRESETS.push({
  id: 'belt', group: 'Oscillators', label: 'Belt stick-slip: \u03c6\u2080 0.8, \u03c6\u2081 1, belt 0.4', kind: 'simulate',
  note: 'A mass on a spring, dragged by a belt at 0.4: it rides the belt (stick) until the spring overcomes the ' +
    'static threshold \u03c6\u2081, slips back with \u03c6\u2080 < \u03c6\u2081, catches the belt again \u2014 a limit cycle.',
  spec: {
    model: { mass: 1, spring: linear,
      damper: { law: 'generalized-coulomb', phi0: 0.8, phi1: 1, belt_velocity: 0.4 } },
    initial: { x: 0, v: 0.4 },
    solver: { kind: 'stick-slip', dt: 0.001, t_end: 30, theta: 0.5 },
    output: { every: 10 },
  },
});
PRESETS.push({
  id: 'stability-1.2', group: 'Stability maps', label: '\u00a71.2 model: \u03bc\u2082 \u00d7 \u03bb', kind: 'stability',
  note: 'F_V + \u03bb F_V\u2032 = \u03bc\u2081 x + \u03bc\u2082 x\u2032 (the model of \u00a71.2 of Babov\u00e1kov\u00e1 2012), swept over \u03bc\u2082 = mu[1] and \u03bb = lambda[1]; the black line is ' +
    'the thesis condition (1.10) \u03bc\u2082 \u2212 \u03bb\u03bc\u2081 = 0.',
  spec: {
    mass: 1, law: { lambda: [1, 0.5], mu: [1, 1] },
    map: { x: { param: 'mu[1]', from: 0, to: 3, steps: 240 }, y: { param: 'lambda[1]', from: 0.05, to: 2, steps: 160 } },
  },
});
PRESETS.push({
  id: 'stability-1.3', group: 'Stability maps', label: '\u00a71.3 model: \u03bb\u2081 \u00d7 \u03bb\u2082', kind: 'stability',
  note: 'F_V + \u03bb\u2081 F_V\u2032 + \u03bb\u2082 F_V\u2033 = \u03bc\u2081 x + \u03bc\u2082 x\u2032 (the model of \u00a71.3 of Babov\u00e1kov\u00e1 2012), swept over \u03bb\u2081 and \u03bb\u2082.',
  spec: {
    mass: 1, law: { lambda: [1, 1, 0.5], mu: [1, 2] },
    map: { x: { param: 'lambda[1]', from: 0, to: 3, steps: 240 }, y: { param: 'lambda[2]', from: 0.01, to: 0.8, steps: 160 } },
  },
});
PRESETS.push({
  id: 'stability-one', group: 'Stability maps', label: 'One law (no map): \u00a71.2 model', kind: 'stability',
  note: 'No map: the verdict, the roots with their error bounds and the Hurwitz minors of one law.',
  spec: { mass: 1, law: { lambda: [1, 0.5], mu: [1, 1] } },
});

// ---- networks (docs/networks.md): drawn by network.js ----
PRESETS.push({
  id: 'chain-3', group: 'Networks of masses', label: '3-mass chain: friction, spring, dashpot', kind: 'simulate',
  note: 'Masses 1, 2, 1.5: node 0 on a spring to the ground with Coulomb friction \u03c6\u2080 0.3, a spring k = 2 to node 1, ' +
    'a dashpot c = 0.1 to node 2, which is shaken by cos 2t. Node 0 slips, sticks and slips again while the others swing.',
  spec: {
    model: {
      masses: [1, 2, 1.5],
      elements: [
        { between: ['ground', 0], spring: linear, damper: { law: 'coulomb', phi0: 0.3, belt_velocity: 0 } },
        { between: [0, 1], spring: { law: 'linear', k: 2 } },
        { between: [1, 2], damper: { law: 'linear', c: 0.1 } },
      ],
      forcing: [{ node: 2, kind: 'harmonic', amplitude: 1, omega: 2, phase: 0 }],
    },
    initial: { x: [1, -0.5, 2], v: [0, 0.3, 0] },
    solver: { kind: 'stick-slip', dt: 0.001, t_end: 20, theta: 0.5 },
    output: { every: 10 },
  },
});

// Burridge-Knopoff in the plate's frame: n blocks, each on a leaf spring kp to the plate (the ground here)
// and with friction against the ground, which moves at -V in this frame (belt_velocity -V); neighbour
// springs kc. The friction is Carlson-Langer velocity weakening: Coulomb phi0 with the rational relaxation
// gamma(z) = alpha phi0 z/(vf + |z|), so a slipping block carries phi0 (1 - alpha |z|/(vf + |z|)) sign z, down to
// (1 - alpha) phi0 when fast (docs/networks.md). Frictions and initial stresses vary from block to block (fixed
// numbers, no randomness): every block starts stuck (v = -V) with its leaf spring at 30-95 % of its friction, so
// the weakest break away first, load their neighbours, and slip fronts run along the chain; blocks stick again
// when their speed relative to the ground falls back to zero, and the plate loads them again: the weakening
// keeps the stick-slip cycles going (constant Coulomb friction would let the chain settle into steady sliding).
// Relaxation is stepped under the n-mass step bound W - h theta sum L b b^T > 0 (refused at /solver/dt past it):
// with L = alpha phi0 / vf <= 0.5 * 2 / 0.05 = 20, h theta L = 0.1 < m = 1, far inside it.
function burridgeKnopoff(n, V, kp, kc, alpha, vf) {
  const elements = [], x = [];
  for (let i = 0; i < n; i++) {
    const phi0 = +(1 + Math.sin(7.3 * i) ** 2).toFixed(3);
    const relaxation = { kind: 'rational', a: +(alpha * phi0).toFixed(4), b: vf };
    elements.push({ between: ['ground', i], spring: { law: 'linear', k: kp }, damper: { law: 'coulomb', phi0, belt_velocity: -V, relaxation } });
    x.push(+(-(phi0 / kp) * (0.3 + 0.65 * Math.sin(3.1 * i) ** 2)).toFixed(3));
  }
  for (let i = 0; i + 1 < n; i++) elements.push({ between: [i, i + 1], spring: { law: 'linear', k: kc } });
  return {
    model: { masses: Array(n).fill(1), elements },
    initial: { x, v: Array(n).fill(-V) },
    solver: { kind: 'stick-slip', dt: 0.01, t_end: 100, theta: 0.5 },
    output: { every: 10 },
  };
}
PRESETS.push({
  id: 'burridge-knopoff', group: 'Networks of masses', label: 'Burridge\u2013Knopoff chain of 60 blocks', kind: 'simulate',
  note: '60 blocks (m = 1) on leaf springs kp = 1 to a plate moving at V = 0.1, neighbour springs kc = 0.5, ' +
    'Carlson\u2013Langer friction against the ground, which moves at \u2212V in the plate\u2019s frame: Coulomb ' +
    '\u03c6\u2080 between 1 and 2 weakened by the relaxation \u03b3 = 0.5 \u03c6\u2080 z/(0.05 + |z|), so a fast block keeps ' +
    'half its friction. In the space\u2013time picture a stuck block is dark (v = \u2212V): the weakest blocks break ' +
    'away, slip fronts run along the chain, blocks stick, the plate loads them again, and the stick\u2013slip cycles ' +
    'go on for the whole run. dt = 0.01 is far inside the step bound h\u03b8L < m (h\u03b8L = 0.1).',
  spec: burridgeKnopoff(60, 0.1, 1, 0.5, 0.5, 0.05),
});

// The Carlson-Langer chain (docs/quakes.md; Carlson & Langer 1989) in the plate's frame: unit masses on unit
// springs to the plate, l^2 between neighbours, friction phi(v) = (1 - sigma)/(1 + 2 alpha |v|/(1 - sigma))
// with static threshold 1 against the ground moving at -nu: generalized Coulomb phi0 = 1 - sigma, phi1 = 1 with
// the rational relaxation a = 1 - sigma, b = (1 - sigma)/(2 alpha). Initial offsets in [-1, 0) from a fixed
// pseudo-random sequence (the same every time) break the chain's symmetry; the run asks for its quake catalogue,
// drawn as the Gutenberg-Richter plot (web/quakes.js). Step bound: h theta 2 alpha = 0.125 < 1.
function carlsonLanger(n, l, sigma, alpha, nu, dt, tEnd) {
  const c = 1 - sigma, elements = [], x = [];
  const damper = { law: 'generalized-coulomb', phi0: c, phi1: 1, belt_velocity: -nu,
    relaxation: { kind: 'rational', a: c, b: +(c / (2 * alpha)).toPrecision(12) } };
  for (let i = 0; i < n; i++) {
    elements.push({ between: ['ground', i], spring: { law: 'linear', k: 1 }, damper });
    const r = Math.sin(12.9898 * (i + 1)) * 43758.5453;
    x.push(-+(r - Math.floor(r)).toFixed(4));
  }
  for (let i = 0; i + 1 < n; i++) elements.push({ between: [i, i + 1], spring: { law: 'linear', k: l * l } });
  return {
    model: { masses: Array(n).fill(1), elements },
    initial: { x },
    solver: { kind: 'stick-slip', dt, t_end: tEnd },
    output: { quakes: true, events: false },
  };
}
PRESETS.push({
  id: 'carlson-langer', group: 'Networks of masses', label: 'Carlson\u2013Langer chain of 100 blocks: quakes', kind: 'simulate',
  note: 'The nondimensional Carlson\u2013Langer chain: \u2113 = 3, \u03c3 = 0.01, \u03b1 = 2.5, plate speed \u03bd = 0.01, ' +
    'T = 800. Friction (1 \u2212 \u03c3)/(1 + 2\u03b1|v|/(1 \u2212 \u03c3)), static threshold 1: generalized Coulomb ' +
    '\u03c6\u2080 = 0.99, \u03c6\u2081 = 1 with the rational relaxation a = 0.99, b = 0.198. The run writes its quake ' +
    'catalogue (output.quakes): every connected slip episode, its size, hypocentre and moment; the ' +
    'Gutenberg\u2013Richter plot is log\u2081\u2080 count against the magnitude \u03bc = ln(moment), with a fitted slope ' +
    '(small events on a line, the chain-wide ones as a bump on the right).',
  spec: carlsonLanger(100, 3, 0.01, 2.5, 0.01, 0.05, 800),
});

// The linear analysis of the 3-mass chain (docs/modes.md): its modes (the Coulomb element left out) and the
// point receptance of node 0 to a harmonic force there, on a log scale with its resonances and antiresonances.
PRESETS.push({
  id: 'modes-chain-3', group: 'Linear analysis (modes)', label: '3-mass chain: modes and response', kind: 'modes',
  note: 'Natural frequencies, mass-normalized shapes (the Coulomb element is set-valued: left out) and |H(\u03c9)| of ' +
    'node 0 to a force at node 0 (a point receptance: an antiresonance between each pair of resonances), both ' +
    'located, not only sampled (resonances red, antiresonances blue).',
  spec: {
    model: { masses: [1, 2, 1.5], elements: [
      { between: ['ground', 0], spring: { law: 'linear', k: 1 }, damper: { law: 'coulomb', phi0: 0.3 } },
      { between: [0, 1], spring: { law: 'linear', k: 2 } },
      { between: [1, 2], spring: { law: 'linear', k: 1 }, damper: { law: 'linear', c: 0.1 } }] },
    force_node: 0, response_node: 0, omega: { from: 0.1, to: 3, points: 400, spacing: 'log' },
  },
});

// Friction whose normal force depends on the motion (docs/right-hand.md): Matrosov & Finogenko's piston and
// hinge, Painlevé's rod, and a run that meets Painlevé's indeterminacy (a second acceleration appears).
const RH = 'Friction with motion-dependent normal force (Painlev\u00e9)';
PRESETS.push({
  id: 'piston-hinge', group: RH, label: 'Piston in an inclined tube with a body on a hinge', kind: 'simulate',
  note: 'Matrosov & Finogenko 1995, \u00a76: a piston (m1 = 1, f1 = 0.2) in a tube at 0.3 rad carries a body (m2 = 1, J_C = 0.1, r = 0.5) ' +
    'on a hinge with friction arm f2 = 0.02. Friction holds the piston while the body swings down, until the force ' +
    'that holds it leaves the cone f1|N1| at t = 0.402; N1 and |N2| depend on the accelerations.',
  spec: {
    model: { kind: 'piston-hinge', m1: 1, m2: 1, J_C: 0.1, r: 0.5, alpha: 0.3, f1: 0.2, f2: 0.02 },
    initial: { x: [0, 0.8], v: [0, 0] },
    solver: { kind: 'right-hand', t_end: 3, dt: 0.01 },
    output: { every: 1 },
  },
});
PRESETS.push({
  id: 'painleve-rod', group: RH, label: 'Painlev\u00e9\u2019s rod falling on a rough floor (\u03bc = 0.5)', kind: 'simulate',
  note: 'A uniform rod (m = 1, length 1) leaning at 1.2 rad on a floor with \u03bc = 0.5 < 4/3: held by friction, then ' +
    'sliding, until it reaches the floor (an impact this model does not follow: the run stops there, shaded).',
  spec: {
    model: { kind: 'painleve-rod', m: 1, length: 1, mu: 0.5 },
    initial: { x: [0, 1.2], v: [0, 0] },
    solver: { kind: 'right-hand', t_end: 1, dt: 0.005 },
    output: { every: 1 },
  },
});
PRESETS.push({
  id: 'painleve-rod-drop', group: RH, label: 'Painlev\u00e9\u2019s rod dropped on a rough floor (\u03bc = 0.3, e = 0.5)',
  kind: 'simulate',
  note: 'The same rod held with its end 0.5 above the floor, let go moving and turning: it lands and bounces ' +
    '(Stronge\u2019s energetic restitution with friction), the bounces accumulate, it comes down sticking and ' +
    'slides until it lies flat (shaded after). The rows\u2019 gap is the end\u2019s height.',
  spec: {
    model: { kind: 'painleve-rod', m: 1, length: 1, mu: 0.3, restitution: 0.5 },
    initial: { x: [0, 1.2, 0.5], v: [0.5, 1, 0] },
    solver: { kind: 'right-hand', t_end: 1.6, dt: 0.002 },
    output: { every: 1 },
  },
});
PRESETS.push({
  id: 'painleve-indeterminacy', group: RH, label: 'A run that meets Painlev\u00e9\u2019s indeterminacy', kind: 'simulate',
  note: 'Both coordinates sliding with f1 = 5.2: at t = 0.0853 a second acceleration appears from infinity and the ' +
    'friction law no longer decides the motion. The run stops there with both candidates (shaded after).',
  spec: {
    model: { kind: 'piston-hinge', m1: 2.2125, m2: 3.6783, J_C: 0.6877, r: 0.4161, alpha: 0.7352, f1: 5.2068, f2: 0.2532 },
    initial: { x: [0, -1.2397], v: [-0.6889, -4.7616] },
    solver: { kind: 'right-hand', t_end: 0.2, dt: 0.001 },
    output: { every: 1 },
  },
});

// Circuits as linear complementarity systems (docs/lcs.md, Cibulka 2014, Examples 1.9 and 1.10): the docs' three
// documents without their "output" (the page asks for about a plot's width of samples), drawn by web/lcs.js.
// `columns` names a row's x, u and w components as [symbol, meaning] (the rows carry only x0, u0, w0, ...);
// the view uses them when the run has as many states and components. Component j pairs u_j with w_j.
const LCS = 'Circuits (linear complementarity systems)';
const rlcLcs = (lcs, law, t_end) => ({
  model: { lcs: { A: [[0, 1], [-4, -0.5]], ...lcs }, laws: [law] },
  initial: { x: [0, 1] },
  solver: { kind: 'stick-slip', dt: 0.001, t_end, theta: 0.5 },
});
PRESETS.push({
  id: 'lcs-rlc-diode', group: LCS, label: 'Series RLC with an ideal diode', kind: 'simulate',
  note: 'R = 0.5, L = 1, C = 0.25, q(0) = 0, i(0) = 1, no source; u = \u2212v_D \u22a5 i. The current falls to 0 at ' +
    't* = atan2(\u03c9_d, \u03b1)/\u03c9_d = 0.7285 with the charge q* = 0.41675; the diode then blocks for good and holds ' +
    '\u2212v_D = q*/C = 1.667.',
  columns: { x: [['q', 'charge'], ['i', 'current']], u: [['\u2212v_D', 'reverse diode voltage']], w: [['i', 'diode current']] },
  spec: rlcLcs({ B: [[0], [1]], C: [[0, 1]], D: [[0]] }, { law: 'complementarity' }, 3),
});
PRESETS.push({
  id: 'lcs-rlc-breakdown', group: LCS, label: 'Series RLC with a breakdown diode (V_b = 0.5)', kind: 'simulate',
  note: 'The same circuit with v_D \u2208 [\u2212V_b, 0], V_b = 0.5 (an interval law). When the current stops, q*/C = 1.667 > V_b ' +
    'breaks the diode down: the current reverses with v_D = \u2212V_b and oscillates about q = C V_b = 0.125.',
  columns: { x: [['q', 'charge'], ['i', 'current']], u: [['v_D', 'diode voltage']], w: [['\u2212i', 'minus the current']] },
  spec: rlcLcs({ B: [[0], [-1]], C: [[0, -1]] }, { law: 'interval', min: -0.5, max: 0 }, 2),
});
const complementarity = { law: 'complementarity' };
PRESETS.push({
  id: 'lcs-bridge', group: LCS, label: 'Four-diode bridge rectifier', kind: 'simulate',
  note: 'R = 1, L = 1, C = 0.5 with Cibulka 2014\u2019s A, B, C, D (Example 1.10); x = (v_C, i_L). Each pair u_j \u22a5 w_j is one diode\u2019s reverse ' +
    'voltage and current. The load current i_DF1 + i_DR1 = |v_C|/R whichever sign v_C has (rectified); the tank is a ' +
    'parallel RLC, v_C = \u22122e^{\u2212t} sin t.',
  columns: {
    x: [['v_C', 'capacitor voltage'], ['i_L', 'inductor current']],
    u: [['\u2212v_DR1', 'DR1 reverse voltage'], ['\u2212v_DF2', 'DF2 reverse voltage'], ['i_DF1', 'DF1 current'], ['i_DR2', 'DR2 current']],
    w: [['i_DR1', 'DR1 current'], ['i_DF2', 'DF2 current'], ['\u2212v_DF1', 'DF1 reverse voltage'], ['\u2212v_DR2', 'DR2 reverse voltage']],
  },
  spec: {
    model: {
      lcs: { A: [[0, -2], [1, 0]], B: [[0, 0, -2, 2], [0, 0, 0, 0]], C: [[0, 0], [0, 0], [-1, 0], [1, 0]],
        D: [[1, 1, -1, 0], [1, 1, 0, -1], [1, 0, 0, 0], [0, 1, 0, 0]] },
      laws: [complementarity, complementarity, complementarity, complementarity],
    },
    initial: { x: [0, 1] },
    solver: { kind: 'stick-slip', dt: 0.001, t_end: 6, theta: 0.5 },
  },
});

// Contacts and impacts (docs/contact.md): a network element with "contact" keeps its elongation
// u = x_b - x_a >= distance (Newton's impact law with restitution e); drawn by web/network.js with
// web/contact.js's phase portrait, contact forces and impact markers.
const CONTACT = 'Contacts and impacts';
PRESETS.push({
  id: 'bouncing-ball', group: CONTACT, label: 'Bouncing ball, e = 0.8', kind: 'simulate',
  note: 'A unit mass dropped from x = 1 under g = 9.81 onto a table at x = 0 (a contact to the ground, ' +
    'restitution e = 0.8). The first impact at t\u2081 = \u221a(2/g) = 0.4515 with speed \u221a(2g) = 4.429, each rebound e times ' +
    'the one before; the impacts accumulate at t\u221e = t\u2081 + 2e\u221a(2g)/(g(1 \u2212 e)) = 4.064, after which the ball ' +
    'rests on the table (F\u2099 = \u2212mg).',
  spec: {
    model: { masses: [1], elements: [{ between: ['ground', 0], contact: { distance: 0, restitution: 0.8 } }],
      forcing: [{ node: 0, kind: 'constant', value: -9.81 }] },
    initial: { x: [1], v: [0] },
    solver: { kind: 'stick-slip', dt: 0.001, t_end: 5, theta: 0.5 },
  },
});
PRESETS.push({
  id: 'impact-oscillator', group: CONTACT, label: 'Impact oscillator: forced spring hitting a stop, e = 0.7',
  kind: 'simulate',
  note: 'm = k = 1 on a spring to the ground, F = 0.5 cos(0.8 t), and a stop at x = \u22120.5 (a second element to the ' +
    'ground with contact distance \u22120.5, e = 0.7). Free of the stop x = (0.5/(1 \u2212 0.8\u00b2))(cos 0.8t \u2212 cos t) ' +
    'until it first reaches \u22120.5 at t = 4.02; then it hits the stop about once per forcing period and the phase ' +
    'portrait jumps from \u2212v to 0.7 v at x = \u22120.5.',
  spec: {
    model: { masses: [1], elements: [
      { between: ['ground', 0], spring: { law: 'linear', k: 1 } },
      { between: ['ground', 0], contact: { distance: -0.5, restitution: 0.7 } }],
    forcing: [{ node: 0, kind: 'harmonic', amplitude: 0.5, omega: 0.8, phase: 0 }] },
    initial: { x: [0], v: [0] },
    solver: { kind: 'stick-slip', dt: 0.001, t_end: 60, theta: 0.5 },
  },
});

// ---- sweeps (docs/sweep.md): drawn by web/sweep.js as the run lines arrive ----
// view: the feature the response curve starts with, and its scale; reference(p, feature): a closed form of the
// first parameter drawn dashed next to the runs (null where it does not apply).
const SWEEP = 'Sweeps (response curves, bifurcation diagrams)';
// Den Hartog 1931: the steady non-stop amplitude of x'' + x + F sgn x' = P cos wt (m = k = 1, so beta = w),
// derived in docs/sweep.md: X / (P/k) = sqrt(1/(1 - b^2)^2 - (F U / P)^2), U = sin(pi/b) / (b (1 + cos(pi/b))).
const denHartog = (FP) => {
  const X = (b) => {
    const U = Math.sin(Math.PI / b) / (b * (1 + Math.cos(Math.PI / b))), r = 1 / (1 - b * b) ** 2 - (FP * U) ** 2;
    return r > 0 ? Math.sqrt(r) : NaN;
  };
  const f = (b, feature) => (feature === 'amplitude' || feature === 'x_max' ? X(b) : feature === 'x_min' ? -X(b)
    : feature === 'period' ? 2 * Math.PI / b : NaN);
  f.label = `Den Hartog 1931, non-stop motion (F/P = ${FP})`;
  return f;
};
const coulombForced = (phi0, dt, tEnd) => ({
  model: { mass: 1, spring: linear, damper: { law: 'coulomb', phi0 },
    forcing: { kind: 'harmonic', amplitude: 1, omega: 1 } },
  solver: { kind: 'stick-slip', dt, t_end: tEnd, theta: 0.5 },
});
PRESETS.push({
  id: 'sweep-den-hartog', group: SWEEP, label: 'Den Hartog: forced Coulomb oscillator, F/P = 0.1, \u03c9 0.5\u20133', kind: 'sweep',
  note: 'x\u2033 + x + 0.1 sgn x\u2032 = cos \u03c9t over 51 frequencies: the amplitude after the transient (t \u2265 800) against ' +
    'Den Hartog 1931\u2019s closed form for non-stop motion (dashed; 10\u207b\u2074 apart away from resonance). At \u03c9 = 1 it ' +
    'grows without bound (F/P < \u03c0/4): about 430 by t = 1000; near it the transient has not died out yet. No ' +
    'section is recorded (a stroboscopic one needs one forcing period). Click a run for its trajectory.',
  view: { feature: 'amplitude', log: true },
  reference: denHartog(0.1),
  spec: {
    base: coulombForced(0.1, 0.01, 1000),
    vary: [{ pointer: '/model/forcing/omega', from: 0.5, to: 3, count: 51 }],
    record: { after: 800 },
  },
});
PRESETS.push({
  id: 'sweep-den-hartog-map', group: SWEEP, label: 'Den Hartog map: time stuck over \u03c9 \u00d7 F/P', kind: 'sweep',
  note: 'The same oscillator over the frequency and the friction force F/P = \u03c6\u2080 (P = 1): the fraction of the time ' +
    'after the transient that it is stuck. Weak friction or fast forcing: non-stop motion (Den Hartog 1931\u2019s ' +
    'regime, 0); strong friction: it sticks for part of every period, at low frequencies whatever the friction.',
  view: { feature: 'stick_fraction', log: false },
  reference: null,
  spec: {
    base: coulombForced(0.1, 0.02, 150),
    vary: [{ pointer: '/model/forcing/omega', from: 0.3, to: 2.5, count: 23 },
      { pointer: '/model/damper/phi0', from: 0.05, to: 0.95, count: 10 }],
    record: { after: 100, features: ['stick_fraction', 'amplitude', 'period'] },
  },
});
// A belt-driven oscillator with velocity weakening, forced: generalized Coulomb (static 1 above dynamic 0.8)
// relaxed by gamma = 0.3 z/(0.5 + |z|), so the sliding friction falls further with the slip speed z, and
// shaken by 0.3 cos 1.3t (as in Popp & Stelter 1990's forced belt-driven oscillators); the stroboscopic
// section at the forcing period 2 pi/1.3 over the belt speed.
PRESETS.push({
  id: 'sweep-belt', group: SWEEP, label: 'Belt-driven, velocity weakening, forced: over the belt speed', kind: 'sweep',
  note: 'm = k = 1 on a belt: generalized Coulomb friction (static 1, dynamic 0.8) weakened further with the slip speed ' +
    '(relaxation \u03b3 = 0.3 z/(0.5 + |z|)) and a force 0.3 cos 1.3t, as in Popp & Stelter 1990\u2019s forced belt-driven ' +
    'oscillators. The stroboscopic section at the forcing period over the belt speed: one point per period (period 1), ' +
    'a few (subharmonic stick\u2013slip), or a cloud (no repeat within 32 periods).',
  view: { feature: 'stick_fraction', log: false },
  reference: null,
  spec: {
    base: {
      model: { mass: 1, spring: linear,
        damper: { law: 'generalized-coulomb', phi0: 0.8, phi1: 1, belt_velocity: 0.4, relaxation: { kind: 'rational', a: 0.3, b: 0.5 } },
        forcing: { kind: 'harmonic', amplitude: 0.3, omega: 1.3 } },
      initial: { x: 0, v: 0.4 },
      solver: { kind: 'stick-slip', dt: 0.005, t_end: 300, theta: 0.5 },
    },
    vary: [{ pointer: '/model/damper/belt_velocity', from: 0.05, to: 1.5, count: 59 }],
    record: { after: 150, section: { period: 2 * Math.PI / 1.3, count: 32 } },
  },
});
