// tests/browser/test_page.mjs - the page at / in a real browser: Debian's Chromium driven by playwright-core
// (never a downloaded browser). Run by tests/test_browser.sh:
//
//   node tests/browser/test_page.mjs DAEMON_URL SCREENSHOT_DIR COUNTS_FILE
//   env PLAYWRIGHT_DIR (a directory whose node_modules holds playwright-core), CHROMIUM (the binary),
//       TOKEN_URL and TOKEN (optional: a daemon that wants that bearer token)
//
// It loads the page, runs presets and waits for each stream to end; the points each plot drew must equal
// the samples streamed (the page's data attributes against the summary line and an independent count of
// the same request's NDJSON); no console error, page error or failed request may occur; the screenshots
// must not be blank (the PNG is decoded here: distinct colours) and every canvas must carry curves (pixels
// of saturated colour). An invalid spec must show its problem+json error at the member its pointer names;
// the stability tab must draw its map; and the page must work behind a path prefix (a small reverse proxy
// below maps /prefix/ to the daemon and refuses everything else). And what a new user found wrong stays
// fixed: picking a preset runs it; the modes charts have ticks, tick labels (no "10^2.0") and legends;
// Painlevé's rod reaching the floor is an ended-at-contact note, not a failure; elastoplastic yield/unload
// events are marked; impulses are stems on the contact-force plot; the bridge's coinciding curves all
// show; the meta line's warnings are shown (a stubbed answer); sources are named, never "seed 00N"; the sweep tab draws a dot per run as the lines
// arrive, each the line's own numbers, marks failed runs, draws the section points and the map, and opens a
// clicked run as its simulate request.
// Prints "ok"/"not ok" lines and writes "PASSED FAILED" to COUNTS_FILE.
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';
import { createRequire } from 'node:module';

const [base, shots, countsFile] = process.argv.slice(2);
const { chromium } = createRequire(path.join(process.env.PLAYWRIGHT_DIR, 'package.json'))('playwright-core');
let passed = 0, failed = 0;

function check(ok, what, why = '') {
  console.log((ok ? 'ok - ' : 'not ok - ') + what + (ok || !why ? '' : '\n    ' + why));
  ok ? passed++ : failed++;
  return ok;
}

function done(code) {
  fs.writeFileSync(countsFile, `${passed} ${failed}\n`);
  process.exit(code);
}
setTimeout(() => { check(false, 'the browser test finished within 300 s'); done(1); }, 300_000).unref();

// ---- a PNG decoder, enough for Chromium's screenshots (8-bit RGB or RGBA, not interlaced) ----
function pngColours(buf) {
  let off = 8, w = 0, h = 0, depth = 0, type = 0, interlace = 0;
  const idat = [];
  while (off < buf.length) {
    const len = buf.readUInt32BE(off), kind = buf.toString('latin1', off + 4, off + 8), data = buf.subarray(off + 8, off + 8 + len);
    if (kind === 'IHDR') [w, h, depth, type, interlace] = [data.readUInt32BE(0), data.readUInt32BE(4), data[8], data[9], data[12]];
    if (kind === 'IDAT') idat.push(data);
    if (kind === 'IEND') break;
    off += 12 + len;
  }
  if (depth !== 8 || (type !== 2 && type !== 6) || interlace) throw new Error(`unexpected PNG: depth ${depth}, type ${type}`);
  const bpp = type === 6 ? 4 : 3, stride = w * bpp, raw = zlib.inflateSync(Buffer.concat(idat));
  let prev = Buffer.alloc(stride), cur = Buffer.alloc(stride), p = 0;
  const colours = new Set();
  for (let y = 0; y < h; y++) {
    const filter = raw[p++];
    for (let x = 0; x < stride; x++) {
      const a = x >= bpp ? cur[x - bpp] : 0, b = prev[x], c = x >= bpp ? prev[x - bpp] : 0;
      let v = raw[p++];
      if (filter === 1) v += a;
      else if (filter === 2) v += b;
      else if (filter === 3) v += (a + b) >> 1;
      else if (filter === 4) {
        const q = a + b - c, pa = Math.abs(q - a), pb = Math.abs(q - b), pc = Math.abs(q - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      cur[x] = v & 255;
    }
    for (let x = 0; x < stride; x += bpp) colours.add(cur.readUIntBE(x, 3));
    [prev, cur] = [cur, prev];
  }
  return { w, h, colours: colours.size };
}

// ---- the browser ----
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'dashpot-chromium-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1440, height: 900 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
process.on('exit', () => fs.rmSync(profile, { recursive: true, force: true }));

// Every console error, page error and failed request, with the page it came from.
const problems = [];
function watch(page, name) {
  page.on('console', (m) => { if (m.type() === 'error') problems.push(`${name}: console: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`${name}: page error: ${e.message}`));
  page.on('requestfailed', (r) => {
    // Chromium reports a fetch whose body was read through a ReadableStream as failed (ERR_ABORTED) about
    // half of the time, even when every byte arrived: a bare reader loop over the same stream in this
    // browser, 40 times, showed 17 such reports (pipeTo 30, res.text() none). A stream's completeness is
    // checked by what the page received (the summary line, the sample count), so these are not problems.
    // The same holds for the sweep's stream (v1/sweep: checked by its summary line and run count).
    if (r.failure()?.errorText === 'net::ERR_ABORTED' && /\/v1\/(simulate|sweep)$/.test(r.url())) return;
    problems.push(`${name}: request failed: ${r.url()} ${r.failure()?.errorText}`);
  });
  const urls = [];
  page.on('request', (r) => urls.push(r.url()));
  return urls;
}
// The problems since `from` that are not expected (the refused request's own "Failed to load resource").
function unexpected(from, allowed) {
  return problems.slice(from).filter((p) => !(allowed && allowed.test(p)));
}

const state = (page, panel) => page.evaluate((id) => {
  const d = document.getElementById(id).dataset;
  // the plots on screen: a network run hides the one-mass plots and shows its own (web/network.js)
  return { ...d, canvases: [...document.querySelectorAll(`#${id} canvas`)].filter((c) => c.offsetParent !== null).map((c) => +c.dataset.points) };
}, panel);

async function waitRun(page, panel, after) {
  await page.waitForFunction(([id, n]) => {
    const d = document.getElementById(id).dataset;
    return +(d.run || 0) > n && ['done', 'error', 'stopped'].includes(d.state);
  }, [panel, after], { timeout: 120_000 });
  return state(page, panel);
}

async function press(page, panel) {
  const before = +((await page.getAttribute('#' + panel, 'data-run')) || 0);
  await page.click('#run');
  return waitRun(page, panel, before);
}

// Picks a preset from the menu, which runs it (no Run pressed: web/app.js), and waits for that run's end.
async function pick(page, id, panel = 'panel-simulate') {
  const before = await page.evaluate(() => Math.max(...['panel-simulate', 'panel-stability', 'panel-modes', 'panel-sweep']
    .map((p) => +(document.getElementById(p).dataset.run || 0))));
  await page.selectOption('#preset', id);
  return waitRun(page, panel, before);
}

// Pixels of saturated colour (curves and markers, not the grey grid, frame and labels) per canvas.
const inked = (page) => page.evaluate(() => [...document.querySelectorAll('#panel-simulate canvas')].filter((c) => c.offsetParent !== null).map((c) => {
  const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
  let n = 0;
  for (let i = 0; i < d.length; i += 4)
    if (d[i + 3] > 160 && Math.max(d[i], d[i + 1], d[i + 2]) - Math.min(d[i], d[i + 1], d[i + 2]) > 60) n++;
  return n;
}));

// The daemon's reports name their sources by author and year, and the page shows them as they come.
const named = (s) => s;

async function screenshot(page, name) {
  const text = await page.evaluate(() => document.body.innerText + ' ' + [...document.querySelectorAll('[title]')].map((e) => e.title).join(' '));
  const labels = text.match(/.{0,30}\b(seed 00\d|issue #?\d+).{0,10}/gi) || [];
  check(labels.length === 0, `${name}: the page names its sources (no "seed 00N", no issue numbers)`, labels.join(' | '));
  const file = path.join(shots, name + '.png');
  const png = await page.screenshot({ path: file });
  const { w, h, colours } = pngColours(png);
  check(w === 1440 && h === 900 && colours >= 64, `screenshot ${file} is not blank (${colours} colours)`,
    `${w} x ${h}, ${colours} distinct colours`);
}

// Runs a simulation preset and checks what the page shows against the daemon's own stream.
async function runPreset(page, name, id, origin) {
  const from = problems.length;
  const d = await pick(page, id);
  const spec = await page.inputValue('#spec');
  // The page sends a request without "output" with output.max_samples = its sample budget (data-budget).
  const budget = +d.budget || 0;
  const stream = async (body) => (await (await fetch(origin + 'v1/simulate', { method: 'POST', body,
    headers: { Accept: 'application/x-ndjson' } })).text()).trim().split('\n').map((l) => JSON.parse(l));
  const full = await stream(spec);
  const lines = budget ? await stream(JSON.stringify({ ...JSON.parse(spec), output: { max_samples: budget } })) : full;
  check(budget > 0 === !('output' in JSON.parse(spec)), `${name}: ${id}: a sample budget (${budget}) is asked for exactly when the request has no output`);
  if (budget) {
    const fullSamples = full.filter((o) => o.type === 'sample').length, every = Math.ceil(full[0].steps / (budget - 1));
    const got = lines.filter((o) => o.type === 'sample').length;
    const width = await page.evaluate(() => document.getElementById('plot-xv').clientWidth * devicePixelRatio);
    check(budget >= Math.min(200, width) && budget <= Math.max(200, 1.01 * width) && +d.every === every && lines[0].every === every &&
      got <= budget && got >= Math.min(budget, fullSamples) / 2,
      `${name}: ${id}: about the plot's width (${width} px) in samples: budget ${budget}, every ${every}, ${got} of ${fullSamples}`,
      JSON.stringify({ budget, every: d.every, got, fullSamples }));
  }
  const chip = await page.evaluate(() => document.getElementById('decimated')?.textContent || '');
  check((+d.every > 1) === /^decimated: 1 sample per/.test(chip) && (!budget || +d.every === 1 || chip.includes('about the plot width')),
    `${name}: ${id}: the page says when the curve is decimated (every ${d.every})`, chip);
  const samples = lines.filter((o) => o.type === 'sample').length;
  const events = lines.filter((o) => o.type === 'event').length;
  const summary = lines[lines.length - 1];
  check(d.state === 'done', `${name}: preset ${id} streams to its end (data-state done)`, JSON.stringify(d));
  check(summary.type === 'summary' && +d.summarySamples === summary.samples && summary.samples === samples,
    `${name}: ${id}: the page read the summary line (samples ${d.summarySamples} = ${samples} sample lines)`);
  check(+d.samples === samples && +d.points === samples,
    `${name}: ${id}: ${samples} samples streamed, ${d.points} held for plotting`, JSON.stringify(d));
  check(d.canvases.length === 5 && d.canvases.every((n) => n === samples),
    `${name}: ${id}: every plot drew ${samples} points`, JSON.stringify(d.canvases));
  check(+d.events === events, `${name}: ${id}: ${events} stick/slip events marked`, `page: ${d.events}`);
  const wp = lines[0].wellposedness;
  const shown = await page.textContent('#wp-body');
  check(shown.includes(named(wp.existence.guaranteed ? wp.existence.theorem : wp.existence.reason)) &&
    shown.includes(named(wp.uniqueness.guaranteed ? wp.uniqueness.theorem : wp.uniqueness.reason)) &&
    wp.checks.every((c) => shown.includes(named(`${c.hypothesis}: ${c.detail}`))) && !/Lipschitz\s+Lipschitz/.test(shown),
    `${name}: ${id}: the meta line's well-posedness report is shown, each check as "hypothesis: detail"`);
  const warned = await page.evaluate(() => [...document.querySelectorAll('#warnings li.warning')].filter((e) => e.offsetParent !== null).length);
  check(warned === (lines[0].warnings || []).length, `${name}: ${id}: the meta line's ${warned} warning(s) shown, no more`,
    JSON.stringify(lines[0].warnings));
  const ink = await inked(page);
  check(ink.every((n) => n > 300), `${name}: ${id}: every canvas carries curves`, `saturated pixels per canvas: ${ink}`);
  const bad = unexpected(from);
  check(bad.length === 0, `${name}: ${id}: no console error, page error or failed request`, bad.join('\n    '));
  return { d, lines, full };
}

// Runs a network preset (web/network.js) and checks what the page shows against the daemon's own stream:
// the samples held and drawn, the per-node curves and their legend, the events, and the space-time picture:
// the share of its pixels in the colour of the slowest velocity (a stuck block on the belt, v = -V) against
// the share of (sample, node) pairs stuck in the stream. Returns what it found for the caller's own checks.
async function runNetworkPreset(page, name, id, origin) {
  const from = problems.length;
  const d = await pick(page, id);
  const spec = await page.inputValue('#spec');
  const res = await fetch(origin + 'v1/simulate', { method: 'POST', body: spec, headers: { Accept: 'application/x-ndjson' } });
  const lines = (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
  const meta = lines[0], samples = lines.filter((o) => o.type === 'sample'), events = lines.filter((o) => o.type === 'event');
  const nodes = meta.columns.nodes.length, curves = Math.min(8, nodes);
  check(d.state === 'done' && meta.model === 'network', `${name}: network preset ${id} streams to its end`, JSON.stringify(d));
  check(+d.samples === samples.length && +d.points === samples.length && +d.summarySamples === samples.length,
    `${name}: ${id}: ${samples.length} samples streamed and held for plotting`, JSON.stringify(d));
  check(d.canvases.length === 3 && d.canvases.every((n) => n === samples.length),
    `${name}: ${id}: the space-time picture and both per-node plots drew ${samples.length} samples (one-mass plots hidden)`,
    JSON.stringify(d.canvases));
  check(+d.events === events.length && events.every((e) => Number.isInteger(e.element) && e.element < meta.elements),
    `${name}: ${id}: ${events.length} events, each naming an element`, `page: ${d.events}`);
  const view = await page.evaluate(() => {
    const box = document.getElementById('network-plots'), c = document.getElementById('plot-spacetime');
    const [l, t, w, h] = c.dataset.area.split(',').map(Number), k = c.width / c.clientWidth;
    const px = c.getContext('2d').getImageData(Math.ceil(l * k), Math.ceil(t * k), Math.floor(w * k) - 1, Math.floor(h * k) - 1).data;
    let dark = 0, all = 0;
    const colours = new Set();
    for (let i = 0; i < px.length; i += 4) {
      if (px[i + 3] === 0) continue; // columns not reached (none once the run is done)
      all++;
      colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
      if (Math.abs(px[i] - 68) + Math.abs(px[i + 1] - 1) + Math.abs(px[i + 2] - 84) < 6) dark++;
    }
    return { nodes: +box.dataset.nodes, curves: +box.dataset.curves, legend: document.getElementById('legend-nodes-x').children.length,
      oneHidden: document.getElementById('plots-one').hidden, dark: dark / Math.max(1, all), all, area: w * h * k * k, colours: colours.size };
  });
  check(view.nodes === nodes && view.curves === curves && view.legend === curves && view.oneHidden,
    `${name}: ${id}: ${nodes} nodes in the picture, ${curves} per-node curves with their legend`, JSON.stringify(view));
  const vmin = Math.min(...samples.map((s) => Math.min(...s.v)));
  const stuck = samples.reduce((a, s) => a + s.v.filter((v) => v === vmin).length, 0) / (samples.length * nodes);
  check(view.all > 0.95 * view.area && Math.abs(view.dark - stuck) < 0.03,
    `${name}: ${id}: the picture is filled and ${(100 * view.dark).toFixed(1)}% of it has the colour of v = ${vmin} ` +
    `(the stream: ${(100 * stuck).toFixed(1)}% of node-samples)`, JSON.stringify(view));
  const ink = await inked(page);
  check(ink.every((n) => n > 300), `${name}: ${id}: every network canvas carries curves or colour`, `saturated pixels: ${ink}`);
  const bad = unexpected(from);
  check(bad.length === 0, `${name}: ${id}: no console error, page error or failed request`, bad.join('\n    '));
  return { d, view, events, stuck, samples, meta };
}

// The Carlson-Langer preset asks for its quakes: the Gutenberg-Richter figure shows, has received every quake
// line of the daemon's own stream, draws its non-empty magnitude bins with a falling fitted line, and carries
// colour; the network plots are drawn as for any network run.
async function checkQuakes(page, origin) {
  const from = problems.length;
  const d = await pick(page, 'carlson-langer');
  const spec = await page.inputValue('#spec');
  const res = await fetch(origin + 'v1/simulate', { method: 'POST', body: spec, headers: { Accept: 'application/x-ndjson' } });
  const lines = (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
  const quakes = lines.filter((o) => o.type === 'quake');
  const g = await page.evaluate(() => {
    const c = document.getElementById('plot-quakes'), f = document.getElementById('quakes-figure');
    const px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let ink = 0;
    for (let i = 0; i < px.length; i += 4)
      if (px[i + 3] > 160 && Math.max(px[i], px[i + 1], px[i + 2]) - Math.min(px[i], px[i + 1], px[i + 2]) > 60) ink++;
    return { shown: !f.hidden && c.offsetParent !== null, quakes: +c.dataset.quakes, bins: +c.dataset.bins,
      slope: c.dataset.slope === '' ? NaN : +c.dataset.slope, ink, legend: document.getElementById('quakes-legend').textContent };
  });
  check(d.state === 'done' && JSON.parse(spec).output.quakes === true && quakes.length >= 100 && g.shown &&
    g.quakes === quakes.length && g.bins >= 5 && g.slope < 0 && g.ink > 300 && g.legend.includes(`${quakes.length} quakes`),
    `carlson-langer: the Gutenberg-Richter plot of its ${quakes.length} quakes (${g.bins} bins, slope ${g.slope})`, JSON.stringify(g));
  const bad = unexpected(from);
  check(bad.length === 0, 'carlson-langer: no console error, page error or failed request', bad.join('\n    '));
  await screenshot(page, 'page-carlson-langer');
}

// Runs a right-hand friction preset (web/right_hand.js) and checks the page against the daemon's own stream:
// the samples held and drawn on its two plots (the one-mass plots hidden), the events, and for a run that
// stops (a Painlevé paradox, the rod at the floor) the stop time the view shades from, read from the record.
// end: 'summary' (runs to t_end), 'error' (a paradox: a failure, shown as the problem) or 'contact' (the
// rod reaching the floor, the end its model is built for: a note, no failure shown anywhere).
async function runRightHandPreset(page, name, id, origin, end) {
  const stops = end !== 'summary';
  const from = problems.length;
  const d = await pick(page, id);
  const spec = await page.inputValue('#spec');
  const res = await fetch(origin + 'v1/simulate', { method: 'POST', body: spec, headers: { Accept: 'application/x-ndjson' } });
  const lines = (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
  const samples = lines.filter((o) => o.type === 'sample'), events = lines.filter((o) => o.type === 'event');
  const last = lines[lines.length - 1];
  check(d.state === (end === 'error' ? 'error' : 'done') && last.type === (stops ? 'error' : 'summary') && d.end === (end === 'contact' ? 'contact' : ''),
    `${name}: right-hand preset ${id} ${{ summary: 'streams to its end', error: 'stops with its record', contact: 'ends at contact' }[end]}`,
    JSON.stringify(d));
  const shown = await page.evaluate(() => ({ status: document.getElementById('status').textContent,
    problem: !document.getElementById('problem').hidden, end: document.getElementById('end-note').hidden ? null : document.getElementById('end-note').textContent.trim(),
    failureClass: [...document.querySelectorAll('.problem')].filter((e) => e.offsetParent !== null).map((e) => e.className) }));
  if (end === 'contact')
    check(!shown.problem && shown.failureClass.length === 0 && !/fail/i.test(shown.status) && /ended at contact/.test(shown.status) &&
      /^Ended at contact/.test(shown.end || '') && shown.end.includes(named(last.detail)) &&
      (await page.textContent('#wp-body')).includes('Framework right-hand solutions (Matrosov & Finogenko 1995):'),
      `${name}: ${id}: reaching the floor is shown as the designed end (a note with the record, "${shown.status}"), not as a failure`,
      JSON.stringify({ shown, last }));
  if (end === 'error')
    check(shown.problem && shown.end === null && shown.status === 'failed', `${name}: ${id}: a paradox is still shown as the run's failure`,
      JSON.stringify(shown));
  check(+d.samples === samples.length && d.canvases.length === 2 && d.canvases.every((n) => n === samples.length),
    `${name}: ${id}: both right-hand plots drew the ${samples.length} samples (one-mass plots hidden)`, JSON.stringify(d));
  check(+d.events === events.length, `${name}: ${id}: ${events.length} events`, `page: ${d.events}`);
  const stop = await page.evaluate(() => document.getElementById('rh-plots').dataset.stop);
  const want = stops ? String(+/at t=([-+0-9.eE]+)/.exec(last.detail)[1]) : '';
  check(stop === want, `${name}: ${id}: the plots are shaded from ${want || 'nowhere'}`, `data-stop ${stop}`);
  const bad = unexpected(from, /status of 422|Failed to load resource/);
  check(bad.length === 0, `${name}: ${id}: no console error, page error or failed request`, bad.join('\n    '));
}

// The document docs/lcs.md gives under `<!-- file: NAME -->` (the LCS presets are those, without "output").
function docsDocument(name) {
  const md = fs.readFileSync(new URL('../../docs/lcs.md', import.meta.url), 'utf8');
  const m = new RegExp(`<!-- file: ${name.replace('.', '\\.')} -->\\s*\`\`\`json\\n([\\s\\S]*?)\`\`\``).exec(md);
  if (!m) throw new Error(`docs/lcs.md has no file ${name}`);
  return JSON.parse(m[1]);
}

// Runs a linear complementarity system preset (web/lcs.js) and checks the page against the daemon's own
// stream of the request the page sent: the docs' document, the samples held and drawn on its three plots
// (the one-mass plots hidden), the preset's column names in the legends, finite data, and each plot's data
// range equal to the stream's over the same columns. Returns the stream and the plots' ranges.
async function runLcsPreset(page, name, id, origin, docFile) {
  const from = problems.length;
  const d = await pick(page, id);
  const spec = JSON.parse(await page.inputValue('#spec')), doc = docsDocument(docFile);
  delete doc.output;
  check(JSON.stringify(spec) === JSON.stringify(doc) && +d.budget > 0,
    `${name}: ${id}: the request is docs/lcs.md's ${docFile} without its output (the page picks the samples: ${d.budget})`,
    JSON.stringify(spec));
  const res = await fetch(origin + 'v1/simulate', { method: 'POST', body: JSON.stringify({ ...spec, output: { max_samples: +d.budget } }),
    headers: { Accept: 'application/x-ndjson' } });
  const lines = (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
  const meta = lines[0], samples = lines.filter((o) => o.type === 'sample'), n = samples.length;
  check(d.state === 'done' && meta.model === 'lcs' && lines[lines.length - 1].type === 'summary' && +d.every === meta.every,
    `${name}: LCS preset ${id} streams to its end (every ${meta.every})`, JSON.stringify(d));
  check(+d.samples === n && +d.points === n && d.canvases.length === 3 && d.canvases.every((k) => k === n),
    `${name}: ${id}: the state, complementarity and phase plots drew the ${n} samples (one-mass plots hidden)`, JSON.stringify(d));
  const view = await page.evaluate(() => {
    const box = document.getElementById('lcs-plots'), text = (i) => document.getElementById(i).textContent;
    const range = (i) => document.getElementById(i).dataset.yrange.split(',').map(Number);
    return { ...box.dataset, xLegend: text('lcs-x-legend'), uwLegend: text('lcs-uw-legend'), oneHidden: document.getElementById('plots-one').hidden,
      x: range('plot-lcs-x'), uw: range('plot-lcs-uw'), phase: range('plot-lcs-phase'), wp: text('wp-body') };
  });
  const preset = JSON.parse(await page.evaluate(async () => JSON.stringify((await import('./presets.js')).PRESETS)))
    .find((p) => p.id === id);
  const said = ([sym, meaning], col) => `${col} = ${sym} (${meaning})`;
  check(view.states === String(meta.states) && view.components === String(meta.components) && view.named === 'true' &&
    preset.columns.x.every((c, j) => view.xLegend.includes(said(c, 'x' + j))) &&
    preset.columns.u.every((c, j) => view.uwLegend.includes(said(c, 'u' + j)) && view.uwLegend.includes(said(preset.columns.w[j], 'w' + j))),
    `${name}: ${id}: the legends name the columns as the preset does (${view.xLegend})`, JSON.stringify(view));
  const span = (cols) => { const v = samples.flatMap((s) => cols.map(([g, j]) => s[g][j])); return [Math.min(...v), Math.max(...v)]; };
  const cols = (g, k) => Array.from({ length: k }, (_, j) => [g, j]);
  const want = { x: span(cols('x', meta.states)), uw: span([...cols('u', meta.components), ...cols('w', meta.components)]), phase: span([['x', 1]]) };
  check(view.finite === 'true' && ['x', 'uw', 'phase'].every((k) => view[k].every(Number.isFinite) && view[k].join() === want[k].join()),
    `${name}: ${id}: finite data, each plot's range that of its columns in the stream`, JSON.stringify({ view, want }));
  check(view.wp.includes(named(meta.step.uniqueness)), `${name}: ${id}: the step's uniqueness is reported (${meta.step.uniqueness})`, view.wp);
  const ink = await inked(page);
  check(ink.every((k) => k > 300), `${name}: ${id}: every LCS canvas carries curves`, `saturated pixels per canvas: ${ink}`);
  const bad = unexpected(from);
  check(bad.length === 0, `${name}: ${id}: no console error, page error or failed request`, bad.join('\n    '));
  return { samples, meta, view };
}

// The closed forms of docs/lcs.md for the three circuits, checked on the stream the page drew (and, for the
// ideal diode, on the page's own plotted range). Series RLC, R = 0.5, L = 1, C = 0.25, q(0) = 0, i(0) = 1:
// i = e^{-at}(cos wd t - (a/wd) sin wd t), a = R/2L, first zero t* = atan2(wd, a)/wd, q* = e^{-at*} sin(wd t*)/wd.
const RLC = (() => {
  const a = 0.25, wd = Math.sqrt(4 - a * a), ts = Math.atan2(wd, a) / wd;
  return { a, wd, C: 0.25, ts, qs: Math.exp(-a * ts) * Math.sin(wd * ts) / wd,
    i: (t) => Math.exp(-a * t) * (Math.cos(wd * t) - (a / wd) * Math.sin(wd * t)) };
})();

async function checkCircuits(page, out) {
  const { a, wd, C, ts, qs } = RLC;
  const rlc = await runLcsPreset(page, 'page', 'lcs-rlc-diode', out, 'rlc.json');
  const s = rlc.samples, k = s.findIndex((r) => r.x[1] === 0), h = rlc.meta.dt * rlc.meta.every;
  const later = s.slice(k), before = s.slice(0, k);
  check(k > 0 && s[k].t >= ts && s[k].t <= ts + h + 1e-9 && later.every((r) => r.x[1] === 0 && r.x[0] === s[k].x[0]) &&
    Math.abs(s[k].x[0] - qs) < 1e-5 && later.every((r) => Math.abs(r.u[0] - qs / C) < 1e-4) &&
    before.every((r) => Math.abs(r.x[1] - RLC.i(r.t)) < 1e-5 && r.u[0] === 0),
    `ideal diode: i follows e^{-at}(cos - (a/wd) sin) until it first vanishes (t = ${s[k]?.t}, t* = ${ts.toFixed(4)}), then stays 0 ` +
    `with q = ${s[k]?.x[0]} = q* (${qs.toFixed(5)}) and -v_D = q*/C`, JSON.stringify(s[k]));
  check(Math.abs(rlc.view.uw[1] - qs / C) < 1e-4 && rlc.view.phase[0] === 0,
    `ideal diode: the page plots -v_D up to q*/C = ${(qs / C).toFixed(4)} (${rlc.view.uw[1]}) and never a negative current`,
    JSON.stringify(rlc.view));
  await screenshot(page, 'page-lcs-rlc');

  // Breakdown, V_b = 0.5: after t* the current reverses with v_D = -V_b about q = C V_b:
  // q = C V_b + y* e^{-as}(cos wd s + (a/wd) sin wd s), s = t - t*, y* = q* - C V_b (O(h) in the switch).
  const bd = await runLcsPreset(page, 'page', 'lcs-rlc-breakdown', out, 'breakdown.json');
  const Vb = 0.5, ys = qs - C * Vb, rev = bd.samples.filter((r) => r.t > ts + 0.005);
  const q = (t) => C * Vb + ys * Math.exp(-a * (t - ts)) * (Math.cos(wd * (t - ts)) + (a / wd) * Math.sin(wd * (t - ts)));
  const err = Math.max(...rev.map((r) => Math.abs(r.x[0] - q(r.t))));
  check(rev.length > 50 && rev.every((r) => r.u[0] === -Vb && r.x[1] < 0) && err < 1e-3,
    `breakdown diode: after t* v_D = -V_b, the current reversed, q about C V_b as the closed form (error ${err.toExponential(2)})`);
  await screenshot(page, 'page-lcs-breakdown');

  // The bridge, R = 1, L = 1, C = 0.5, v_C(0) = 0, i_L(0) = 1: a parallel RLC, v_C = -2 e^{-t} sin t, and the
  // load current i_DF1 + i_DR1 = u2 + w0 = |v_C|/R whichever sign v_C has.
  const br = await runLcsPreset(page, 'page', 'lcs-bridge', out, 'bridge.json');
  const vErr = Math.max(...br.samples.map((r) => Math.abs(r.x[0] + 2 * Math.exp(-r.t) * Math.sin(r.t))));
  const load = Math.max(...br.samples.map((r) => Math.abs(r.u[2] + r.w[0] - Math.abs(r.x[0]))));
  check(vErr < 5e-4 && load < 1e-9 && br.samples.some((r) => r.x[0] > 1e-3) && br.samples.some((r) => r.x[0] < -1e-3),
    `bridge: v_C = -2e^{-t} sin t (error ${vErr.toExponential(2)}) changes sign, the load current is |v_C|/R (error ${load.toExponential(1)})`);
  // Its curves pair up: u0 = u2 = w1 = w3 and u1 = u3 = w0 = w2 throughout; drawn one over another, the last
  // drawn of each group would hide the rest (components 0 and 1 nowhere to be seen): each of the four
  // components' colours must show on the complementarity plot, and the legend must say which coincide.
  const bv = await page.evaluate(() => {
    const c = document.getElementById('plot-lcs-uw'), px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const colours = [[0, 114, 178], [213, 94, 0], [0, 158, 115], [204, 121, 167]], n = [0, 0, 0, 0];
    for (let i = 0; i < px.length; i += 4)
      colours.forEach(([r, g, b], k) => { if (Math.abs(px[i] - r) + Math.abs(px[i + 1] - g) + Math.abs(px[i + 2] - b) < 40) n[k]++; });
    return { coincide: document.getElementById('lcs-plots').dataset.coincide, legend: document.getElementById('lcs-uw-legend').textContent, n };
  });
  check(bv.coincide === 'u0=u2=w1=w3;u1=u3=w0=w2' && bv.legend.includes('coincide: u0 = u2 = w1 = w3; u1 = u3 = w0 = w2') &&
    bv.n.every((k) => k > 150),
    `bridge: the coinciding curves are told apart (alternating dashes, every component's colour shows: ${bv.n} pixels) and the legend says they coincide`,
    JSON.stringify(bv));
  await screenshot(page, 'page-lcs-bridge');

  // An edited request with one state (x' = -x - 2 + u, 0 <= u ⊥ x >= 0, x(0) = 1): the preset's names no
  // longer fit, so the columns are x0, u0, w0, and there is no phase portrait. x = 3e^{-t} - 2 reaches 0 at
  // t = ln 1.5; from then on u = 2 holds it there: the complementarity plot's top is u's 2 (w = x is at most 1).
  const from = problems.length;
  await page.fill('#spec', JSON.stringify({ model: { lcs: { A: [[-1]], B: [[1]], C: [[1]], D: [[0]], p: [-2] },
    laws: [{ law: 'complementarity' }] }, initial: { x: [1] }, solver: { kind: 'stick-slip', dt: 0.001, t_end: 2, theta: 0.5 } }));
  const d = await press(page, 'panel-simulate');
  const one = await page.evaluate(() => ({ ...document.getElementById('lcs-plots').dataset,
    phaseHidden: document.getElementById('lcs-phase-figure').hidden, legend: document.getElementById('lcs-uw-legend').textContent,
    uw: document.getElementById('plot-lcs-uw').dataset.yrange.split(',').map(Number),
    x: document.getElementById('plot-lcs-x').dataset.yrange.split(',').map(Number) }));
  check(d.state === 'done' && one.named === 'false' && one.phaseHidden && d.canvases.length === 2 && one.legend === 'u0w0',
    'an edited one-state LCS: columns named x0, u0, w0 (not the preset\'s), no phase portrait', JSON.stringify({ d, one }));
  check(Math.abs(one.uw[1] - 2) < 1e-6 && one.uw[0] === 0 && Math.abs(one.x[0]) < 1e-12 && one.x[1] === 1,
    `an edited one-state LCS: x falls from 1 to 0 and u = 2 holds it there (page: u, w in [${one.uw}], x in [${one.x}])`);
  const extra = unexpected(from);
  check(extra.length === 0, 'the edited LCS: no console error', extra.join('\n    '));
}

// Runs a contact preset (web/contact.js on top of web/network.js) and checks the page against the daemon's
// own stream of the request the page sent (with its sample budget): one node, so the space-time picture is
// hidden and x(t), v(t), the phase portrait and the contact forces are drawn, each through the samples and
// the two rows added at each impact (v before and after, at x = u of the contact to the ground); the
// impacts marked are the stream's; finite data; the x and phase plots' ranges are the stream's over the
// samples and the impacts' states. Returns the stream and the plots' ranges for the closed-form checks.
async function runContactPreset(page, name, id, origin) {
  const from = problems.length;
  const d = await pick(page, id);
  const spec = JSON.parse(await page.inputValue('#spec'));
  const res = await fetch(origin + 'v1/simulate', { method: 'POST', body: JSON.stringify({ ...spec, output: { max_samples: +d.budget } }),
    headers: { Accept: 'application/x-ndjson' } });
  const lines = (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
  const meta = lines[0], samples = lines.filter((o) => o.type === 'sample'), summary = lines[lines.length - 1];
  const impacts = lines.filter((o) => o.type === 'event' && o.kind === 'impact'), rows = samples.length + 2 * impacts.length;
  check(d.state === 'done' && meta.model === 'network' && summary.type === 'summary' && +d.budget > 0 && +d.every === meta.every,
    `${name}: contact preset ${id} streams to its end (every ${meta.every})`, JSON.stringify(d));
  const view = await page.evaluate(() => {
    const box = document.getElementById('network-plots'), range = (i) => document.getElementById(i).dataset.yrange.split(',').map(Number);
    return { ...box.dataset, spaceTimeHidden: document.getElementById('plot-spacetime').closest('figure').hidden,
      x: range('plot-nodes-x'), v: range('plot-nodes-v'), phase: range('plot-contact-phase'), fn: range('plot-contact-fn'),
      fnLegend: document.getElementById('legend-contact-fn').textContent, stems: +document.getElementById('plot-contact-fn').dataset.stems,
      stemInk: (() => { // pixels of the impact colour (#cc79a7) on the force plot: the stems (no force curve has it)
        const c = document.getElementById('plot-contact-fn'), px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let n = 0;
        for (let i = 0; i < px.length; i += 4) if (Math.abs(px[i] - 204) + Math.abs(px[i + 1] - 121) + Math.abs(px[i + 2] - 167) < 30) n++;
        return n;
      })() };
  });
  check(view.stems === impacts.length && view.stemInk > 20 * Math.min(impacts.length, 20) && /impulse at each impact/.test(view.fnLegend),
    `${name}: ${id}: the ${impacts.length} impulses are drawn as stems on the contact-force plot (${view.stemInk} pixels), with a legend`,
    JSON.stringify({ stems: view.stems, stemInk: view.stemInk, legend: view.fnLegend }));
  check(+d.samples === samples.length && +view.impacts === impacts.length && +view.impactRows === 2 * impacts.length &&
    +d.points === rows && d.canvases.length === 4 && d.canvases.every((k) => k === rows) && view.spaceTimeHidden,
    `${name}: ${id}: x(t), v(t), phase portrait and contact forces drew the ${samples.length} samples and 2 rows at each of ` +
    `the ${impacts.length} impacts (${rows}; no space-time picture for one node)`, JSON.stringify({ d, view }));
  const span = (v) => [Math.min(...v), Math.max(...v)];
  const want = { x: span([...samples.map((s) => s.x[0]), ...impacts.map((e) => e.u)]),
    phase: span([...samples.map((s) => s.v[0]), ...impacts.flatMap((e) => [e.du, e.du_after])]) };
  check(view.finite === 'true' && view.contacts === '1' && /rigid/.test(view.fnLegend) &&
    ['x', 'phase', 'fn'].every((k) => view[k].every(Number.isFinite)) && view.x.join() === want.x.join() && view.phase.join() === want.phase.join(),
    `${name}: ${id}: finite data; x in [${view.x}] and v in [${view.phase}] as the stream's samples and impacts`, JSON.stringify({ view, want }));
  const ink = await inked(page);
  check(ink.every((k) => k > 300), `${name}: ${id}: every contact-run canvas carries curves`, `saturated pixels per canvas: ${ink}`);
  const bad = unexpected(from);
  check(bad.length === 0, `${name}: ${id}: no console error, page error or failed request`, bad.join('\n    '));
  return { samples, impacts, summary, view };
}

// The closed forms of the two contact presets. The ball (h0 = 1, g = 9.81, e = 0.8): impact k at
// t_k = t1 + 2 v1 (e + ... + e^{k-1}) / g with t1 = sqrt(2/g), v1 = sqrt(2g), rebound e^k v1, accumulation at
// t_inf = t1 + 2 v1 e / (g (1 - e)), then at rest on the table (Fn = -mg). The impact oscillator
// (m = k = 1, F = 0.5 cos 0.8t, x(0) = v(0) = 0, stop x >= -0.5, e = 0.7): before the first impact
// x = (0.5 / (1 - 0.64)) (cos 0.8t - cos t), so the first impact is the first root of x = -0.5.
async function checkContacts(page, out) {
  const g = 9.81, e = 0.8, t1 = Math.sqrt(2 / g), v1 = Math.sqrt(2 * g), tInf = t1 + 2 * v1 * e / (g * (1 - e));
  const ball = await runContactPreset(page, 'page', 'bouncing-ball', out);
  const I = ball.impacts, tk = (k) => t1 + 2 * v1 * Array.from({ length: k }, (_, j) => e ** (j + 1)).reduce((a, b) => a + b, 0) / g;
  check(I.length >= 10 && Math.abs(I[0].t - t1) < 1e-9 && Math.abs(I[0].du + v1) < 1e-9 && Math.abs(I[0].du_after - e * v1) < 1e-9,
    `ball: first impact at t = ${I[0]?.t} (sqrt(2/g) = ${t1.toFixed(10)}), speed ${I[0]?.du} -> ${I[0]?.du_after} (-sqrt(2g), e sqrt(2g))`,
    JSON.stringify(I[0]));
  check(I.slice(0, 8).every((o, k) => Math.abs(o.t - tk(k)) < 1e-8 && Math.abs(o.du_after - e ** (k + 1) * v1) < 1e-8 && Math.abs(o.u) < 1e-12),
    'ball: the first 8 impacts at the closed-form times t_k, at x = 0, rebounding at e^k sqrt(2g)', JSON.stringify(I.slice(0, 8).map((o) => [o.t, o.du_after])));
  const f = ball.summary.final;
  check(Math.abs(I[I.length - 1].t - tInf) < 1e-6 && Math.abs(f.x[0]) < 1e-12 && f.v[0] === 0 && Math.abs(f.Fn[0] + g) < 1e-9,
    `ball: the impacts accumulate at t = ${I[I.length - 1].t} (t_inf = ${tInf.toFixed(8)}) and it rests on the table, Fn = ${f.Fn[0]} = -mg`);
  check(Math.abs(ball.view.phase[0] + v1) < 1e-9 && Math.abs(ball.view.phase[1] - e * v1) < 1e-9 && ball.view.x[0] > -1e-12 && ball.view.x[1] === 1 &&
    Math.abs(ball.view.fn[0] + g) < 1e-9,
    `ball: the page's phase portrait spans v in [-sqrt(2g), e sqrt(2g)] = [${ball.view.phase}], x never below the table (${ball.view.x[0]})`);
  await screenshot(page, 'page-bouncing-ball');

  const osc = await runContactPreset(page, 'page', 'impact-oscillator', out);
  const A = 0.5 / (1 - 0.8 ** 2), x = (t) => A * (Math.cos(0.8 * t) - Math.cos(t)), dx = (t) => A * (Math.sin(t) - 0.8 * Math.sin(0.8 * t));
  let [a, b] = [3, 4.5]; // x(3) > -0.5 > x(4.5), and x stays above -0.5 on [0, 3]
  for (let i = 0; i < 100; i++) { const m = (a + b) / 2; if (x(m) + 0.5 > 0) a = m; else b = m; }
  const J = osc.impacts, ts = (a + b) / 2;
  check(J.length >= 5 && Math.abs(J[0].t - ts) < 1e-5 && Math.abs(J[0].du - dx(ts)) < 1e-6,
    `impact oscillator: first impact at t = ${J[0]?.t} with du = ${J[0]?.du} (closed form ${ts.toFixed(7)}, ${dx(ts).toFixed(7)})`);
  check(J.every((o) => Math.abs(o.u + 0.5) < 1e-12 && o.du < 0 && Math.abs(o.du_after + 0.7 * o.du) < 1e-12 * Math.abs(o.du)),
    `impact oscillator: all ${J.length} impacts at the stop x = -0.5, each rebounding at -0.7 times the incoming rate`);
  check(Math.abs(osc.view.x[0] + 0.5) < 1e-12 && osc.samples.every((s) => s.x[0] >= -0.5 - 1e-12),
    `impact oscillator: x never below the stop beyond rounding (page: min x ${osc.view.x[0]})`);
  await screenshot(page, 'page-impact-oscillator');
}

// ---- sweeps (web/sweep.js) ----
// The NDJSON lines of POST v1/sweep of a document, fetched here (not through the page).
const sweepLines = async (origin, body) => (await (await fetch(origin + 'v1/sweep', { method: 'POST', body,
  headers: { Accept: 'application/x-ndjson' } })).text()).trim().split('\n').map((l) => JSON.parse(l));
const sweepView = (page) => page.evaluate(() => {
  const pts = (id) => [...document.querySelectorAll(`#${id} circle.pt`)].map((c) => ({ i: +c.dataset.index, x: c.dataset.x, y: c.dataset.y, cx: +c.getAttribute('cx') }));
  const ds = (id) => document.getElementById(id).dataset;
  return { panel: { ...ds('panel-sweep') }, dots: pts('sweep-curve'), curve: ds('sweep-curve').points, bif: ds('sweep-bif').points,
    map: ds('sweep-map').points, cells: document.querySelectorAll('#sweep-map rect.cell').length,
    failed: [...document.querySelectorAll('#sweep-curve path.failed')].map((e) => +e.dataset.index),
    failedList: document.getElementById('sweep-failed').hidden ? '' : document.getElementById('sweep-failed').textContent,
    reference: (document.querySelector('#sweep-curve path.reference')?.getAttribute('d').match(/[ML]/g) || []).length,
    bifShown: document.getElementById('sweep-bif').closest('figure').offsetParent !== null, // an <svg> has no offsetParent
    mapShown: document.getElementById('sweep-map').closest('figure').offsetParent !== null };
});
// Den Hartog 1931's steady non-stop amplitude of x'' + x + F sgn x' = cos(beta t) (docs/sweep.md).
const denHartogX = (b, FP) => { const U = Math.sin(Math.PI / b) / (b * (1 + Math.cos(Math.PI / b))); return Math.sqrt(1 / (1 - b * b) ** 2 - (FP * U) ** 2); };

// Opens a run by clicking `selector` and returns the simulate request the page sent (its "output" apart: the
// page asks for 10 001 samples, the daemon's default, not its plot-width budget that would alias a long
// forced run), the simulate panel's state, the note and the editor's document (output apart too).
async function openRun(page, selector) {
  const posts = [], onPost = (r) => { if (r.method() === 'POST' && r.url().endsWith('/v1/simulate')) posts.push(r.postData()); };
  page.on('request', onPost);
  const before = await page.evaluate(() => Math.max(...['panel-simulate', 'panel-stability', 'panel-modes', 'panel-sweep']
    .map((p) => +(document.getElementById(p).dataset.run || 0))));
  await page.click(selector);
  const d = await waitRun(page, 'panel-simulate', before);
  page.off('request', onPost);
  const outputs = [], sent = posts.map((b) => { const o = JSON.parse(b); outputs.push(o.output); delete o.output; return o; });
  const editor = JSON.parse(await page.inputValue('#spec'));
  delete editor.output;
  return { d, sent, outputs, visible: await page.isVisible('#panel-simulate'), note: await page.textContent('#preset-note'), editor };
}

async function checkSweeps(page, origin) {
  let from = problems.length;
  // Den Hartog's response curve: as many dots as runs, each the line's own numbers, drawn as the lines arrive.
  await page.evaluate(() => {
    window.sweepSeen = [];
    new MutationObserver(() => window.sweepSeen.push(+document.getElementById('sweep-curve').dataset.points))
      .observe(document.getElementById('sweep-curve'), { attributes: true, attributeFilter: ['data-points'] });
  });
  let d = await pick(page, 'sweep-den-hartog', 'panel-sweep');
  const text = await page.inputValue('#spec'), doc = JSON.parse(text);
  const lines = await sweepLines(origin, text), runs = lines.filter((o) => o.type === 'run'), summary = lines[lines.length - 1];
  let v = await sweepView(page);
  check(d.state === 'done' && runs.length === 51 && summary.completed === 51 && +v.panel.runs === 51 && +v.panel.received === 51 &&
    v.dots.length === 51 && +v.curve === 51 && +v.panel.failed === 0,
    `sweep: Den Hartog's preset draws a dot per run (${v.dots.length} dots, ${runs.length} run lines)`, JSON.stringify({ d, panel: v.panel, curve: v.curve }));
  const byIndex = new Map(runs.map((r) => [r.index, r]));
  const agree = v.dots.every((p) => byIndex.has(p.i) && +p.x === byIndex.get(p.i).values[0] && +p.y === byIndex.get(p.i).features.amplitude);
  const order = [...v.dots].sort((a, b) => +a.x - +b.x), monotone = order.every((p, k) => !k || p.cx > order[k - 1].cx);
  check(agree && monotone && new Set(v.dots.map((p) => p.i)).size === 51,
    'sweep: each dot is its run line\'s omega and amplitude, exactly, placed in the order of omega', JSON.stringify(v.dots.slice(0, 3)));
  const seen = await page.evaluate(() => window.sweepSeen);
  check(seen.some((n) => n > 0 && n < 51), `sweep: the curve is drawn as the lines arrive (dots drawn along the way: ${[...new Set(seen)].slice(0, 12).join(' ')})`);
  // The daemon's amplitudes against Den Hartog's closed form, away from resonance (where the transient is
  // over by t = 800): the page draws the same closed form dashed.
  const far = runs.filter((r) => Math.abs(r.values[0] - 1) > 0.25 && r.values[0] > 0.52);
  const worst = Math.max(...far.map((r) => Math.abs(r.features.amplitude / denHartogX(r.values[0], 0.1) - 1)));
  check(far.length > 35 && worst < 1e-3 && v.reference > 300 && !v.bifShown,
    `sweep: ${far.length} amplitudes within ${worst.toExponential(1)} of Den Hartog's closed form, drawn dashed (${v.reference} points); no section, no diagram`);
  await page.hover('#sweep-curve circle.pt[data-index="20"]');
  const hover = await page.textContent('#sweep-hover');
  check(/^run 20 \(ω = 1\.5\): amplitude = 0\.79\d* — click/.test(hover), 'sweep: pointing at a dot reads its run', hover);
  await screenshot(page, 'page-sweep-den-hartog');
  // A click opens the run: the base document with the run's omega, sent to v1/simulate, drawn in the simulate tab.
  let o = await openRun(page, '#sweep-curve circle.pt[data-index="20"]');
  const want = structuredClone(doc.base);
  want.model.forcing.omega = byIndex.get(20).values[0];
  check(o.visible && o.d.state === 'done' && o.sent.length === 1 && JSON.stringify(o.sent[0]) === JSON.stringify(want) &&
    JSON.stringify(o.editor) === JSON.stringify(want) && JSON.stringify(o.outputs) === '[{"max_samples":10001}]' &&
    o.d.canvases.length === 5 && o.d.canvases.every((n) => n === +o.d.summarySamples && n === 10001) &&
    o.note.startsWith('Run 20 of the sweep: /model/forcing/omega = 1.5'),
    'sweep: a click on a dot opens its run: the base with omega = 1.5 sent to v1/simulate, its 10 001 samples drawn', JSON.stringify({ ...o, editor: 0 }));
  await screenshot(page, 'page-sweep-trajectory');
  // Back to the sweep tab (the sweep document is still in its editor): a run that fails is shown, not dropped.
  await page.click('#tab-sweep');
  check(JSON.parse(await page.inputValue('#spec')).vary[0].pointer === '/model/forcing/omega', 'sweep: the sweep tab keeps its document');
  const bad = { base: { ...doc.base, solver: { kind: 'stick-slip', dt: 0.01, t_end: 20, theta: 0.5 } },
    vary: [{ pointer: '/model/mass', values: [1, -1, 2] }], record: { after: 10 } };
  await page.fill('#spec', JSON.stringify(bad, null, 2));
  d = await press(page, 'panel-sweep');
  v = await sweepView(page);
  check(d.state === 'done' && +v.panel.received === 3 && +v.panel.failed === 1 && v.dots.length === 2 && v.failed.join() === '1' &&
    /1 run failed/.test(v.failedList) && v.failedList.includes('/model/mass') && v.failedList.includes('422'),
    'sweep: a run that fails (mass -1) is a red cross and a line naming /model/mass; the others are drawn', JSON.stringify(v));
  // A bad sweep document: the 422 names the member by its pointer into the sweep document.
  await page.fill('#spec', JSON.stringify({ ...bad, vary: [{ pointer: '/nope/x', values: [1] }] }, null, 2));
  d = await press(page, 'panel-sweep');
  const problem = await page.textContent('#problem');
  check(d.state === 'error' && problem.includes('/vary/0/pointer') && problem.trim().startsWith('422'),
    'sweep: a bad sweep document is its 422, by pointer into the sweep document', problem);
  let extra = unexpected(from, /status of 422/);
  check(extra.length === 0, 'the sweep tab: no console error', extra.join('\n    '));
  // The belt: the bifurcation diagram draws every section point of every run.
  from = problems.length;
  d = await pick(page, 'sweep-belt', 'panel-sweep');
  const belt = (await sweepLines(origin, await page.inputValue('#spec'))).filter((l) => l.type === 'run');
  v = await sweepView(page);
  const points = belt.reduce((n, r) => n + r.section.length, 0), periods = belt.map((r) => new Set(r.section.map((p) => p[1].toFixed(4))).size);
  check(d.state === 'done' && +v.bif === points && points > 20 * belt.length && v.bifShown && v.dots.length === belt.length &&
    periods.includes(1) && periods.some((n) => n >= 2 && n <= 8) && periods.some((n) => n > 16),
    `sweep: the belt's bifurcation diagram draws the ${points} section points of ${belt.length} runs (period 1, a few, a cloud: ` +
    `${[...new Set(periods)].sort((a, b) => a - b).join(' ')} distinct x)`, JSON.stringify(v.panel));
  await screenshot(page, 'page-sweep-belt');
  // The period where it has none (no repeat within 32 section points: a cloud) is an open dot on the bottom
  // edge, its reason in its tooltip, not a missing run.
  await page.selectOption('#sweep-feature', 'period');
  const nulls = belt.filter((r) => r.features.period === null);
  const shown = await page.evaluate(() => ({ nulls: +document.getElementById('panel-sweep').dataset.nulls,
    marks: [...document.querySelectorAll('#sweep-curve circle.null')].map((c) => [+c.dataset.index, c.textContent]),
    dots: document.querySelectorAll('#sweep-curve circle.pt').length }));
  check(nulls.length > 5 && shown.nulls === nulls.length && shown.dots === belt.length - nulls.length &&
    JSON.stringify(shown.marks.map((m) => m[0]).sort((a, b) => a - b)) === JSON.stringify(nulls.map((r) => r.index).sort((a, b) => a - b)) &&
    shown.marks.every(([i, t]) => t.includes(belt.find((r) => r.index === i).null.period)),
    `sweep: the belt's ${nulls.length} runs without a period are open dots with the line's reason, the other ${shown.dots} drawn`,
    JSON.stringify(shown).slice(0, 400));
  // Two parameters: the map colours a cell per run; a cell clicked opens its run with both values put.
  d = await pick(page, 'sweep-den-hartog-map', 'panel-sweep');
  const mapDoc = JSON.parse(await page.inputValue('#spec'));
  const grid = (await sweepLines(origin, JSON.stringify(mapDoc))).filter((l) => l.type === 'run');
  v = await sweepView(page);
  check(d.state === 'done' && grid.length === 230 && +v.map === 230 && v.cells === 230 && v.dots.length === 230 && v.mapShown &&
    v.panel.feature === 'stick_fraction', 'sweep: the 23 x 10 map colours 230 cells, the curves draw 230 dots of stick_fraction', JSON.stringify(v.panel));
  await screenshot(page, 'page-sweep-map');
  const r = grid.find((l) => l.index === 47); // omega index 4, phi0 index 7
  o = await openRun(page, '#sweep-map rect.cell[data-index="47"]');
  const want2 = structuredClone(mapDoc.base);
  want2.model.forcing.omega = r.values[0];
  want2.model.damper.phi0 = r.values[1];
  check(o.d.state === 'done' && o.sent.length === 1 && JSON.stringify(o.sent[0]) === JSON.stringify(want2),
    `sweep: a map cell opens its run with both values put (omega ${r.values[0]}, phi0 ${r.values[1]})`, JSON.stringify(o.sent));
  extra = unexpected(from);
  check(extra.length === 0, 'the sweep presets: no console error', extra.join('\n    '));
}

const out = base.endsWith('/') ? base : base + '/';
try {
  // ---- the page at / ----
  const page = await browser.newPage();
  const urls = watch(page, 'page');
  await page.goto(out);
  const first = await waitRun(page, 'panel-simulate', 0);
  check(first.state === 'done', 'the page loads and its default preset streams to its end', JSON.stringify(first));
  check((await page.title()).startsWith('dashpot'), 'the page has its title');
  const presetTexts = await page.evaluate(async () => (await import('./presets.js')).PRESETS.map((p) => `${p.id}: ${p.label} ${p.note}`));
  const unnamed = presetTexts.filter((t) => /seed 00\d|issue #?\d/i.test(t));
  check(unnamed.length === 0 && presetTexts.some((t) => t.includes('Matrosov & Finogenko 1995')),
    `the ${presetTexts.length} presets' notes name their sources (no "seed 00N", no issue numbers)`, unnamed.join('\n    '));

  const thesis = await runPreset(page, 'page', 'thesis-4-gamma', out);
  check(thesis.full.length > 10000 && thesis.lines.length < 1200, 'thesis x0 = 4 with gamma: 10001 samples of dt = 1e-3 over T = 10, ' +
    `the page fetched ${thesis.lines.length - 2}`);
  await screenshot(page, 'page-thesis');
  const belt = await runPreset(page, 'page', 'belt', out);
  check(+belt.d.bands >= 4, `belt: the stick phases are shaded (${belt.d.bands} intervals)`);
  await screenshot(page, 'page-belt');
  await runPreset(page, 'page', 'counter-gc-motion', out);
  const ep = await runPreset(page, 'page', 'elastoplastic', out);
  const yields = ep.lines.filter((o) => o.type === 'event' && o.kind === 'yield').length;
  const offsets = new Set(ep.lines.filter((o) => o.type === 'sample').map((o) => o.p));
  check(yields >= 10 && offsets.size > 10,
    `elastoplastic: the spring yields (${yields} times) and its offset p moves (${offsets.size} values in the samples)`);
  const unloads = ep.lines.filter((o) => o.type === 'event' && o.kind === 'unload').length;
  const epView = await page.evaluate(() => {
    const purple = (id) => { // pixels of the yield markers' colour (#6a3d9a), which no curve has
      const c = document.getElementById(id), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 106) + Math.abs(d[i + 1] - 61) + Math.abs(d[i + 2] - 154) < 30) n++;
      return n;
    };
    const legend = [...document.querySelectorAll('#plots-one .legend [data-kind]')].filter((e) => e.offsetParent !== null).map((e) => e.dataset.kind);
    return { xv: document.getElementById('plot-xv').dataset.markers, phase: document.getElementById('plot-phase').dataset.markers,
      ink: [purple('plot-xv'), purple('plot-phase')], legend: [...new Set(legend)].sort().join() };
  });
  check(/H\u00f6schl 1983, section 15/.test(await page.textContent('#wp-body')),
    'elastoplastic: the well-posedness check names its source (H\u00f6schl 1983, section 15)');
  const want = `yield:${yields},unload:${unloads}`;
  check(epView.xv === want && epView.phase === want && epView.ink.every((n) => n > 20 * yields) && epView.legend === 'unload,yield',
    `elastoplastic: the ${yields} yield and ${unloads} unload events are marked on x(t) and the phase portrait, with their legend`,
    JSON.stringify(epView));
  await screenshot(page, 'page-elastoplastic');

  // ---- networks (web/network.js) ----
  const chain = await runNetworkPreset(page, 'page', 'chain-3', out);
  check(chain.meta.nodes === 3 && chain.events.every((e) => e.element === 0) && chain.events.some((e) => e.kind === 'stick'),
    'chain-3: the Coulomb element 0 sticks and slips (events name it)', JSON.stringify(chain.events.slice(0, 3)));
  await screenshot(page, 'page-chain-3');
  const bk = await runNetworkPreset(page, 'page', 'burridge-knopoff', out);
  const kinds = (k) => bk.events.filter((e) => e.kind === k).length;
  check(bk.meta.nodes >= 50 && kinds('stick') >= 30 && kinds('slip') >= 30 && bk.stuck > 0.05 && bk.stuck < 0.95 && bk.view.colours >= 32,
    `burridge-knopoff: ${bk.meta.nodes} blocks stick-slip visibly (${kinds('stick')} sticks, ${kinds('slip')} slips, ` +
    `${(100 * bk.stuck).toFixed(1)}% stuck, ${bk.view.colours} colours in the picture)`);
  // Velocity weakening (rational relaxation on every block) sustains the cycles: the last third of the run
  // has at least half the sticks of the first third and 60 or more (169, 177, 197 per third; the same chain
  // with constant friction settles into steady sliding: 61, 25, 20).
  const T = bk.meta.t_end, third = (a, b) => bk.events.filter((e) => e.kind === 'stick' && e.t >= a * T / 3 && e.t < b * T / 3).length;
  const relaxed = JSON.parse(await page.inputValue('#spec')).model.elements.filter((e) => e.damper && e.damper.relaxation).length;
  check(relaxed === 60 && bk.meta.events_mode === 'locate' && third(2, 3.01) >= 0.5 * third(0, 1) && third(2, 3.01) >= 60,
    `burridge-knopoff: velocity weakening on ${relaxed} blocks sustains the stick-slip (sticks per third of the run: ` +
    `${third(0, 1)}, ${third(1, 2)}, ${third(2, 3.01)})`);
  await screenshot(page, 'page-burridge-knopoff');
  // ---- the quake catalogue of a Carlson-Langer chain (web/quakes.js, docs/quakes.md) ----
  await checkQuakes(page, out);
  // ---- contacts and impacts (web/contact.js) ----
  await checkContacts(page, out);
  // ---- friction with motion-dependent normal force (web/right_hand.js) ----
  await runRightHandPreset(page, 'page', 'piston-hinge', out, 'summary');
  await screenshot(page, 'page-piston-hinge');
  await runRightHandPreset(page, 'page', 'painleve-indeterminacy', out, 'error');
  await screenshot(page, 'page-painleve-indeterminacy');
  await runRightHandPreset(page, 'page', 'painleve-rod', out, 'contact');
  await screenshot(page, 'page-painleve-rod');
  // ---- circuits as linear complementarity systems (web/lcs.js) ----
  await checkCircuits(page, out);
  // back to one mass: the one-mass plots return, with the samples of the new run. Picked while another
  // preset (the 60-block chain) is still running: that run stops and the page is the new one's.
  await page.selectOption('#preset', 'burridge-knopoff');
  const belt2 = await runPreset(page, 'page', 'belt', out);
  check(belt2.d.canvases.length === 5, 'after a network run a one-mass preset shows its five plots again');

  // ---- an invalid spec: the error at the member its pointer names ----
  let from = problems.length;
  const bad = '{\n  "model": {\n    "mass": -1,\n    "spring": {"law": "linear", "k": 1},\n' +
    '    "damper": {"law": "coulomb", "phi0": 0.3}\n  },\n  "solver": {"dt": 0.001, "t_end": 1}\n}\n';
  await page.fill('#spec', bad);
  let d = await press(page, 'panel-simulate');
  check(d.state === 'error', 'an invalid spec ends the run in the error state');
  const shown = await page.evaluate(() => {
    const box = (el) => el && el.getBoundingClientRect().toJSON();
    const mark = document.querySelector('#editor mark'), msg = document.querySelector('#editor .msg');
    return { lines: document.getElementById('editor').dataset.errorLines, mark: mark && mark.textContent,
      msg: msg && msg.textContent, markBox: box(mark), msgBox: box(msg),
      title: document.getElementById('problem-title').textContent, list: document.getElementById('problem-list').textContent };
  });
  check(shown.lines === '3' && shown.mark === '"mass": -1', 'the pointer /model/mass marks "mass": -1 on line 3 of the editor',
    JSON.stringify(shown));
  check(/must be a finite number > 0/.test(shown.msg || ''), 'the message is written in the editor', JSON.stringify(shown.msg));
  check(shown.markBox && shown.msgBox && Math.abs(shown.markBox.top - shown.msgBox.top) < 4 && shown.msgBox.left >= shown.markBox.right,
    'the message stands next to the marked member, on its line', JSON.stringify([shown.markBox, shown.msgBox]));
  check(shown.title.startsWith('422') && shown.list.includes('/model/mass') && shown.list.includes('line 3'),
    'the problem document is listed under the editor (status, pointer, line)', shown.title + ' | ' + shown.list);
  let extra = unexpected(from, /status of 422/);
  check(extra.length === 0, 'the invalid spec causes no other console error', extra.join('\n    '));
  // The plots of the previous run stay, marked stale, and the preset menu no longer names its preset.
  const stale = () => page.evaluate(() => {
    const panel = document.getElementById('panel-simulate'), note = document.getElementById('stale-note');
    return { stale: panel.dataset.stale, note: note.hidden ? '' : note.textContent, menu: document.getElementById('preset').value,
      menuText: document.getElementById('preset').selectedOptions[0]?.textContent,
      opacity: +getComputedStyle(panel.querySelector('.plots')).opacity,
      previous: document.querySelector('#preset option[value="belt"]').textContent }; // the last run: belt2 above
  });
  let st = await stale();
  check(st.stale === 'true' && st.note.startsWith('Stale:') && st.note.includes(st.previous) && st.note.includes('(422)') && st.opacity < 1,
    'after a 422 the previous plots are marked stale, naming the run they are from', JSON.stringify(st));
  check(st.menu === '' && st.menuText === '(edited request)', 'after a 422 of an edited request the preset menu says "(edited request)"',
    JSON.stringify(st));
  check(d.canvases.every((n) => n > 0), 'the stale plots are still drawn', JSON.stringify(d.canvases));
  await screenshot(page, 'page-invalid');

  from = problems.length;
  await page.fill('#spec', '{"model": {"mass": 1,, "spring": {"law": "linear"}}}');
  d = await press(page, 'panel-simulate');
  const malformed = await page.evaluate(() => ({ lines: document.getElementById('editor').dataset.errorLines,
    mark: document.querySelector('#editor mark')?.textContent, title: document.getElementById('problem-title').textContent }));
  check(d.state === 'error' && malformed.lines === '1' && malformed.mark === ',' && /^400 .*malformed JSON near byte/.test(malformed.title),
    'malformed JSON: the 400 marks the byte where the daemon stopped reading', JSON.stringify(malformed));
  extra = unexpected(from, /status of 400/);
  check(extra.length === 0, 'the malformed spec causes no other console error', extra.join('\n    '));
  st = await stale();
  check(st.stale === 'true' && st.note.includes('(400)'), 'after a 400 the plots stay marked stale', JSON.stringify(st));
  // Picking a preset runs it (one POST, no Run pressed); its answer clears the stale mark.
  const posts = [], onPost = (r) => { if (r.method() === 'POST' && r.url().endsWith('/v1/simulate')) posts.push(r.postData()); };
  page.on('request', onPost);
  d = await pick(page, 'forced');
  page.off('request', onPost);
  st = await stale();
  const sent = posts.map((b) => JSON.parse(b)), editorSpec = JSON.parse(await page.inputValue('#spec'));
  check(d.state === 'done' && posts.length === 1 && JSON.stringify(sent[0].model) === JSON.stringify(editorSpec.model) && st.menu === 'forced',
    `picking a preset runs it: ${posts.length} POST v1/simulate of the preset's request, no Run pressed`, JSON.stringify({ d, posts: posts.length }));
  check(st.stale === 'false' && st.note === '' && st.opacity === 1, 'the picked preset\'s run clears the stale mark', JSON.stringify(st));

  // ---- the stability tab ----
  from = problems.length;
  d = await pick(page, 'stability-1.2', 'panel-stability');
  check(await page.isVisible('#panel-stability'), 'a stability preset opens the stability tab (and runs)');
  const map = await page.evaluate(() => {
    const img = document.getElementById('stab-img');
    return { complete: img.complete, w: img.naturalWidth, h: img.naturalHeight, src: img.src, info: document.getElementById('stab-info').textContent };
  });
  check(d.state === 'done' && map.complete && map.w > 500 && map.h > 400 && map.src.startsWith('blob:'),
    'the stability map (image/svg+xml) is drawn', JSON.stringify(map));
  check(/asymptotically stable/.test(map.info) && /unstable/.test(map.info), 'the map\'s verdict counts are shown (JSON)', map.info);
  d = await pick(page, 'stability-one', 'panel-stability');
  const model = await page.textContent('#stab-model');
  check(d.state === 'done' && model.includes('stable iff (1.10) mu2 - lambda*mu1 > 0; here mu2 - lambda*mu1 = 0.5') && !/> 0 =/.test(model),
    'one law: the thesis condition and the value of its left side, not "> 0 = 0.5"', model);
  extra = unexpected(from);
  check(extra.length === 0, 'the stability map: no console error', extra.join('\n    '));
  await screenshot(page, 'page-stability');

  // ---- the modes tab: frequencies as bars, the shapes, the point receptance with its located extrema ----
  from = problems.length;
  d = await pick(page, 'modes-chain-3', 'panel-modes');
  check(await page.isVisible('#panel-modes'), 'a modes preset opens the modes tab (and runs)');
  const mv = await page.evaluate(() => {
    const ds = document.getElementById('panel-modes').dataset;
    const charts = [...document.querySelectorAll('#panel-modes svg.chart')];
    const ticks = (id, which) => [...document.querySelectorAll(`#${id} .axis.${which} text.tick`)].map((t) => t.textContent);
    const inside = (a, b) => a.x >= b.x && a.y >= b.y && a.x + a.width <= b.x + b.width && a.y + a.height <= b.y + b.height;
    const frame = document.querySelector('#modes-bars rect.frame').getBBox();
    return { state: ds.state, modes: ds.modes, res: ds.resonances, anti: ds.antiresonances,
      points: charts.map((c) => c.dataset.points),
      drawn: [document.querySelectorAll('#modes-bars rect.bar').length, document.querySelectorAll('#modes-shapes circle.node').length,
        (document.querySelector('#modes-response path.curve')?.getAttribute('d').match(/[ML]/g) || []).length],
      barsY: ticks('modes-bars', 'y'), barsX: ticks('modes-bars', 'x'), shapesX: ticks('modes-shapes', 'x'), shapesY: ticks('modes-shapes', 'y'),
      respX: ticks('modes-response', 'x'), respY: ticks('modes-response', 'y'),
      titles: [...document.querySelectorAll('#panel-modes .axis text.title')].map((t) => t.textContent),
      text: [...document.querySelectorAll('#panel-modes svg text')].map((t) => t.textContent).join(' | '),
      valuesInside: [...document.querySelectorAll('#modes-bars text.value')].map((t) => inside(t.getBBox(), frame)),
      legends: ['modes-bars-legend', 'modes-shapes-legend', 'modes-response-legend'].map((id) => document.getElementById(id).children.length),
      shapesLegend: document.getElementById('modes-shapes-legend').textContent, info: document.getElementById('modes-info').textContent };
  });
  // three masses, the Coulomb element left out: 3 modes, 3 resonances, and a point receptance has an
  // antiresonance between each pair of resonances: 2
  check(d.state === 'done' && mv.modes === '3' && mv.res === '3' && mv.anti === '2',
    'the modes tab: 3 modes, 3 resonances and 2 antiresonances of the point receptance', JSON.stringify(mv));
  check(JSON.stringify(mv.points) === '["3","9","400"]' && JSON.stringify(mv.drawn) === '[3,9,400]',
    'the modes tab draws 3 bars, 3 shapes of 3 nodes and the 400-point response curve', JSON.stringify(mv));
  const plain = (l) => /^\u2212?\d+(\.\d+)?$/.test(l);
  check(mv.barsY.length >= 3 && mv.barsY.every(plain) && mv.barsX.join() === '1,2,3' && mv.respX.length >= 3 && mv.respY.length >= 3,
    `the modes tab: the \u03c9 axes have tick labels (bars: ${mv.barsY.join(' ')}; response: ${mv.respX.join(' ')}), the bars are numbered`,
    JSON.stringify(mv));
  check(mv.shapesX.join() === '0,1,2' && mv.shapesY.length >= 3 && mv.shapesY.every(plain) && mv.legends[1] === 3 &&
    /mode 1, \u03c9 = 0\.3889/.test(mv.shapesLegend) && mv.legends[0] === 3 && mv.legends[2] === 3,
    'the modes tab: the shapes have node and amplitude ticks and a legend naming each mode and its \u03c9', JSON.stringify(mv));
  check(!mv.text.includes('^') && [...mv.respX, ...mv.respY].every((l) => plain(l) || /^(\d\u00d7)?10\u2212?\d+$/.test(l)) &&
    mv.respY.includes('1') && mv.respY.includes('10'),
    `the modes tab: log axes labelled as numbers (|H|: ${mv.respY.join(' ')}), never "10^2.0"`, mv.text);
  check(mv.valuesInside.length === 3 && mv.valuesInside.every(Boolean), 'the modes tab: each bar\'s value is drawn inside the frame',
    JSON.stringify(mv.valuesInside));
  check(mv.titles.join() === 'ω (rad/s),mode,amplitude,node,ω (rad/s),|H(ω)|', 'the modes tab: every axis has its title', mv.titles.join());
  check(/1 set-valued element\(s\) left out/.test(mv.info), 'the modes tab says the Coulomb element is left out', mv.info);
  extra = unexpected(from);
  check(extra.length === 0, 'the modes tab: no console error', extra.join('\n    '));
  await screenshot(page, 'page-modes');
  // ---- the sweep tab (web/sweep.js) ----
  await checkSweeps(page, out);
  check(urls.every((u) => u.startsWith(out) || u.startsWith('blob:') || u.startsWith('data:')),
    'every request of the page went to the daemon', urls.filter((u) => !u.startsWith(out)).join(' '));
  await page.close();

  // ---- the meta line's warnings (a stubbed answer: the daemon may not send them yet) ----
  from = problems.length;
  const page4 = await browser.newPage();
  watch(page4, 'warnings');
  const warnings = [{ code: 'dt-vs-period', detail: 'the step 0.5 is longer than a tenth of the shortest natural period 6.28', pointer: '/solver/dt' },
    { code: 'sample-budget', detail: 'every 7 chosen to keep 300 samples', pointer: '/output' }];
  const stubbed = [{ type: 'meta', version: 'stub', solver: 'stick-slip', variant: 'exact', theta: 0.5, dt: 0.5, t_end: 3, steps: 6, every: 7,
    spring: 'linear', damper: 'coulomb', warnings },
  ...[0, 1, 2, 3].map((t) => ({ type: 'sample', t, x: 1 - t / 4, v: -0.25, Fs: 1 - t / 4, Fd: -0.25, Fc: -0.25, phase: 'slip' })),
  { type: 'summary', final: { t: 3, x: 0.25, v: -0.25, Fs: 0.25, Fd: -0.25, Fc: -0.25, phase: 'slip' }, steps: 6, samples: 4, events: 0, stick_time: 0 }];
  await page4.route((u) => u.pathname.endsWith('/v1/simulate'), (r) => r.fulfill({ status: 200, contentType: 'application/x-ndjson',
    body: stubbed.map((o) => JSON.stringify(o)).join('\n') + '\n' }));
  await page4.goto(out + '#belt');
  d = await waitRun(page4, 'panel-simulate', 0);
  const ws = await page4.evaluate(() => {
    const items = [...document.querySelectorAll('#warnings li.warning')].filter((e) => e.offsetParent !== null);
    const status = document.getElementById('status').getBoundingClientRect(), box = document.getElementById('warnings').getBoundingClientRect();
    return { texts: items.map((e) => e.textContent), bg: items.map((e) => getComputedStyle(e).backgroundColor),
      gap: box.top - status.bottom, lines: items.map((e) => e.querySelector('button')?.textContent || '') };
  });
  const yellow = (c) => { const [r, g, b] = c.match(/\d+/g).map(Number); return r > 230 && g > 220 && b < 210; };
  check(d.state === 'done' && ws.texts.length === 2 && warnings.every((w, i) => ws.texts[i].includes(w.detail) && ws.texts[i].includes(w.pointer)) &&
    ws.bg.every(yellow) && ws.gap >= 0 && ws.gap < 60 && /^line \d+$/.test(ws.lines[0]),
    'the meta line\'s warnings: a yellow note each under the run status, with its detail, pointer and the member\'s line', JSON.stringify(ws));
  await screenshot(page4, 'page-warnings');
  await page4.unroute((u) => u.pathname.endsWith('/v1/simulate'));
  await page4.close();
  extra = unexpected(from);
  check(extra.length === 0, 'the warnings page: no console error', extra.join('\n    '));

  // ---- behind a path prefix: a reverse proxy maps /prefix/ to the daemon, nothing else ----
  const target = new URL(out), strays = [], revalidated = [];
  const proxy = http.createServer((req, res) => {
    if (req.url === '/prefix') { res.writeHead(301, { Location: '/prefix/' }); res.end(); return; }
    if (!req.url.startsWith('/prefix/')) {
      strays.push(req.url);
      res.writeHead(404, { 'Content-Type': 'text/plain' });
      res.end('outside /prefix/\n');
      return;
    }
    const up = http.request({ host: target.hostname, port: target.port, method: req.method, headers: req.headers,
      path: req.url.slice('/prefix'.length) }, (r) => {
      if (req.headers['if-none-match'] && r.statusCode === 304) revalidated.push(req.url);
      res.writeHead(r.statusCode, r.headers);
      r.pipe(res);
    });
    up.on('error', (e) => { res.writeHead(502); res.end(String(e)); });
    req.pipe(up);
  });
  await new Promise((resolve) => proxy.listen(0, '127.0.0.1', resolve));
  const prefixed = `http://127.0.0.1:${proxy.address().port}/prefix/`;
  from = problems.length;
  const page2 = await browser.newPage();
  const urls2 = watch(page2, 'prefix');
  await page2.goto(prefixed);
  const first2 = await waitRun(page2, 'panel-simulate', 0);
  check(first2.state === 'done', `under ${prefixed}: the page loads and its default preset streams`, JSON.stringify(first2));
  await runPreset(page2, 'prefix', 'forced', prefixed);
  await screenshot(page2, 'prefix-forced');
  await page2.reload();
  await waitRun(page2, 'panel-simulate', 0);
  check(revalidated.some((u) => u.endsWith('/app.js')),
    'a reload revalidates the files (If-None-Match, 304 through the proxy)', revalidated.join(' '));
  check(strays.length === 0 && urls2.every((u) => u.startsWith(prefixed)),
    'under the prefix every request stays below /prefix/ (relative URLs)', strays.join(' ') + ' ' + urls2.filter((u) => !u.startsWith(prefixed)).join(' '));
  extra = unexpected(from);
  check(extra.length === 0, 'under the prefix: no console error, page error or failed request', extra.join('\n    '));
  proxy.close();
  // ---- a daemon with a bearer token: the page asks for it on the 401 and then runs ----
  if (process.env.TOKEN_URL) {
    from = problems.length;
    const page3 = await browser.newPage();
    watch(page3, 'token');
    await page3.goto(process.env.TOKEN_URL + '#belt');
    d = await waitRun(page3, 'panel-simulate', 0);
    check(d.state === 'error' && await page3.isVisible('#token-form') && (await page3.textContent('#problem-title')).startsWith('401'),
      'with --token-file: the 401 is shown and the page asks for the token', JSON.stringify(d));
    await page3.fill('#token', process.env.TOKEN);
    await page3.click('#token-form button');
    d = await waitRun(page3, 'panel-simulate', +d.run);
    check(d.state === 'done' && +d.points === +d.summarySamples && d.canvases.every((n) => n === +d.summarySamples) &&
      !(await page3.isVisible('#token-form')), 'with the token the run streams to its end', JSON.stringify(d));
    extra = unexpected(from, /status of 401/);
    check(extra.length === 0, 'the token page: no other console error', extra.join('\n    '));
    await page3.close();
  }
} catch (e) {
  check(false, 'the browser test ran to its end', e.stack || String(e));
}
const all = unexpected(0, /status of (422|400|401)/);
check(all.length === 0, 'no unexpected console error anywhere', all.join('\n    '));
await browser.close();
done(failed ? 1 : 0);
