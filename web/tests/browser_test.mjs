// Browser test of the demo page: headless Chromium drives every demo with the mouse to
// scripted positions, reads the verdicts and numbers from the page and compares them with
// the native library's answers for the same inputs (web/tests/native_answers.cpp).
//
//   node web/tests/browser_test.mjs SITE_DIR NATIVE_ANSWERS OUT_DIR
//
// SITE_DIR: the built page (build/web/site); NATIVE_ANSWERS: the native program;
// OUT_DIR: screenshots (one per scenario, page.png) and results.json. Exit status 1 on
// any mismatch, unexpected verdict or console error.
import {chromium} from 'playwright-core';
import {execFileSync} from 'node:child_process';
import {createServer} from 'node:http';
import {mkdirSync, readFileSync, writeFileSync} from 'node:fs';
import {extname, join, resolve} from 'node:path';

const [site, nativeProgram, out] = process.argv.slice(2).map((p) => resolve(p));
if (!out) {
  console.error('usage: node browser_test.mjs SITE_DIR NATIVE_ANSWERS OUT_DIR');
  process.exit(2);
}
mkdirSync(out, {recursive: true});

// Numbers agree when within this relative difference (the wasm build's libm and its
// 128-bit long double round differently from the native ones).
const TOLERANCE = 1e-9;
// The page must answer a drag within this (mean query time per frame, ms); the mesh slide
// makes n (n + 1) / 2 + n rounds for a slide of n (it replays them: web/src/answers.cpp);
// the geometry demo's inscribed ellipse is a barrier method in long double, which the wasm
// build computes in 128-bit software floating point.
const FRAME_BUDGET_MS = {mesh_slide: 3, geometry: 10};
// Counts that follow the arithmetic: the inscribed ellipse's Newton steps in the wasm
// build's 128-bit long double against the native 80-bit one (the answers agree to TOLERANCE).
const STEP_COUNTS = new Set(['inscribe.iterations']);
const STEP_COUNT_TOLERANCE = 0.1;
const budget = (demo) => FRAME_BUDGET_MS[demo] ?? 1;

const types = {'.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm'};
const server = createServer((req, res) => {
  const path = join(site, new URL(req.url, 'http://x').pathname.replace(/\/$/, '/index.html'));
  try {
    const body = readFileSync(path);
    res.writeHead(200, {'Content-Type': types[extname(path)] || 'application/octet-stream'});
    res.end(body);
  } catch {
    res.writeHead(404);
    res.end();
  }
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const url = `http://127.0.0.1:${server.address().port}/`;

const failures = [];
const fail = (msg) => { failures.push(msg); console.log('FAIL ' + msg); };

const browser = await chromium.launch({executablePath: '/usr/bin/chromium', args: ['--no-sandbox']});
const page = await browser.newPage({viewport: {width: 1100, height: 900}});
const consoleErrors = [];
page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
page.on('pageerror', (e) => consoleErrors.push(String(e)));

const started = Date.now();
await page.goto(url);
await page.waitForSelector('[data-testid=status][data-ready=true]', {timeout: 30000});
console.log(`page ready in ${Date.now() - started} ms`);

// ---- actions -------------------------------------------------------------------------

// A press on the canvas at a world point (the geometry demo adds a point there), or, with
// shift held, on a handle (the geometry demo removes it).
async function press(demo, to, shift = false) {
  await page.locator('#' + demo).scrollIntoViewIfNeeded();
  const at = await page.evaluate(([d, p]) => window.ellipsectDemo.client(d, p), [demo, to]);
  if (shift) await page.keyboard.down('Shift');
  await page.mouse.click(at[0], at[1]);
  if (shift) await page.keyboard.up('Shift');
}

async function drag(demo, handle, to) {
  await page.locator('#' + demo).scrollIntoViewIfNeeded();
  const from = await page.evaluate(([d, h]) => window.ellipsectDemo.handleClient(d, h), [demo, handle]);
  const target = await page.evaluate(([d, p]) => window.ellipsectDemo.client(d, p), [demo, to]);
  await page.mouse.move(from[0], from[1]);
  await page.mouse.down();
  await page.mouse.move(target[0], target[1], {steps: 4});
  await page.mouse.up();
}

const testid = (id) => page.locator(`[data-testid="${id}"]`);

// What the page shows for a demo: its inputs, its table of values (exact, from
// data-value), its verdict class and headline, and the drawn polygons.
async function readDemo(demo) {
  const params = JSON.parse(await testid(demo + '-params').textContent());
  const shown = await page.evaluate((d) => {
    const values = {};
    for (const td of document.querySelectorAll(`td[data-testid^="${d}:"]`))
      values[td.dataset.testid.slice(d.length + 1)] = JSON.parse(td.dataset.value);
    const demo = window.ellipsectDemo.demos[d], answer = demo.answer;
    for (const key of Object.keys(answer))  // drawn, not tabulated
      if ((demo.hidden || []).some((h) => key.startsWith(h)))
        values[key] = typeof answer[key] === 'object' ? Array.from(answer[key]) : answer[key];
    return values;
  }, demo);
  const head = testid(demo + '-headline');
  return {params, shown, verdict: await head.getAttribute('data-verdict'), headline: await head.textContent()};
}

// ---- scenarios -------------------------------------------------------------------------

// Each: a name, the demo, the actions, and what must be shown (key: value) afterwards.
const scenarios = [
  {name: 'ellipse_circle-separated', demo: 'ellipse_circle',
   actions: [['drag', 'c.center', [4, 3]]], expect: {'closed.verdict': 'no_collision', exact: 'no_collision'}},
  {name: 'ellipse_circle-collision', demo: 'ellipse_circle',
   actions: [['drag', 'c.center', [2.5, 1.5]]], expect: {'closed.verdict': 'collision', exact: 'collision'}},
  {name: 'ellipse_circle-early-out', demo: 'ellipse_circle',
   actions: [['drag', 'c.center', [0, 0.5]]], expect: {'closed.verdict': 'early_out', exact: 'collision'}},
  {name: 'ellipse_circle-closed-form-fails', demo: 'ellipse_circle',  // a circle: b^2 - 1 = 0
   actions: [['drag', 'c.center', [4, 3]], ['drag', 'e.axis0', [1, 0]], ['drag', 'e.axis1', [-1, 2]]],
   expect: {'closed.status': 'failed', 'quartic.status': 'outside', 'quartic.verdict': 'no_collision'}},

  {name: 'segment_circle-separated', demo: 'segment_circle',
   actions: [['drag', 's.b', [3, 1]]], expect: {verdict: 'no_collision', side: 'right'}},
  {name: 'segment_circle-collision-right', demo: 'segment_circle',
   actions: [['drag', 'c.center', [0, -1]]], expect: {verdict: 'collision', side: 'right'}},
  {name: 'segment_circle-collision-left', demo: 'segment_circle',
   actions: [['drag', 'c.center', [-1, 0]]], expect: {verdict: 'collision', side: 'left'}},

  {name: 'polygonal-circle-collision', demo: 'polygonal',
   actions: [['drag', 'c.center', [2, 1]]], expect: {verdict: 'collision'}},
  {name: 'polygonal-circle-separated', demo: 'polygonal',
   actions: [['drag', 'c.center', [4, 4]]], expect: {verdict: 'no_collision'}},
  {name: 'polygonal-circle-undecided', demo: 'polygonal',
   actions: [['level', '1'], ['drag', 'c.center', [2.5, 2.875]]], expect: {verdict: 'undecided', level: 1}},
  {name: 'polygonal-circle-cover', demo: 'polygonal',
   actions: [['cover', true], ['level', '10']], expect: {}},
  {name: 'polygonal-parallel-collision', demo: 'polygonal',
   actions: [['cover', false], ['body', 'parallel'], ['drag', 'b.center', [2, 1]]], expect: {verdict: 'collision'}},
  {name: 'polygonal-rotated-separated', demo: 'polygonal',
   actions: [['body', 'rotated'], ['drag', 'b.center', [5, 3.5]]], expect: {verdict: 'no_collision'}},
  {name: 'polygonal-rotated-bisections', demo: 'polygonal',
   actions: [['drag', 'b.center', [0.875, 3.125]]], expect: {verdict: 'no_collision', level: 4}},

  {name: 'swept-overlapping-at-start', demo: 'swept',
   actions: [['drag', 'b.center', [-3, 0]]], expect: {status: 'overlapping_at_start'}},
  {name: 'swept-no-contact', demo: 'swept',
   actions: [['drag', 'b.center', [4, 1.5]], ['drag', 'b.velocity', [5, 3]], ['time', '2']],
   expect: {status: 'no_contact_in_window'}},
  {name: 'swept-hit', demo: 'swept',
   actions: [['drag', 'b.velocity', [2.5, 1]], ['click', 'swept-to-contact']], expect: {status: 'hit', relation_t: 'touching'}},

  {name: 'relation-separated', demo: 'relation',
   actions: [['drag', 'b.center', [5, 3]]], expect: {relation: 'separated', 'crossings.count': 0, area: 0}},
  {name: 'relation-overlapping', demo: 'relation',
   actions: [['drag', 'b.center', [2, 0.5]]], expect: {relation: 'overlapping', 'distance.status': 'overlapping'}},

  {name: 'slide-free', demo: 'slide',
   actions: [['drag', 'target', [0, 2]]], expect: {status: 'moved', contacts: 0}},
  {name: 'slide-along-the-floor', demo: 'slide',
   actions: [['drag', 'target', [1, -4.5]]], expect: {status: 'slid', contacts: 1, last_contact: 0}},
  {name: 'slide-into-a-corner', demo: 'slide',
   actions: [['drag', 'target', [-6.875, -4.875]]], expect: {status: 'slid', contacts: 2}},

  // The level's triangles: 0, 1 floor; 2, 3 step; 4, 5 slope; 6 ramp; 7, 8 and 9, 10 the blocks
  // either side of the gap; 11 triangular block; 12 post (a segment); 13 ceiling (a segment).
  // `stays`: where the end center must be, short of the triangles the target lies beyond.
  {name: 'mesh_slide-free', demo: 'mesh_slide',
   actions: [['drag', 'target', [1.5, -1]]], expect: {status: 'moved', contacts: 0, rounds: 1, relation: 'separated'}},
  {name: 'mesh_slide-down-the-slope-along-the-step', demo: 'mesh_slide',
   actions: [['drag', 'target', [0, -4.5]]], stays: ([, y]) => y > -3.25,
   expect: {status: 'slid', contacts: 2, rounds: 3, hits: '5,3', relation: 'touching', touched: '3'}},
  {name: 'mesh_slide-against-the-post', demo: 'mesh_slide',
   actions: [['drag', 'e.center', [4.25, 0.25]], ['drag', 'target', [6.75, 0.25]]], stays: ([x]) => x < 5.5,
   expect: {status: 'slid', contacts: 1, rounds: 2, hits: '12', relation: 'touching', touched: '12'}},
  {name: 'mesh_slide-starts-inside', demo: 'mesh_slide',
   actions: [['drag', 'e.center', [-3, 0.75]]],
   expect: {status: 'overlapping_at_start', rounds: 0, relation: 'overlapping', 'relation.triangle': 7}},
  {name: 'mesh_slide-upright-through-the-gap', demo: 'mesh_slide',
   actions: [['drag', 'e.center', [-0.875, 3]], ['drag', 'e.axis0', [-0.875, 4]], ['drag', 'target', [-0.875, -1.5]]],
   expect: {status: 'moved', contacts: 0, rounds: 1, relation: 'separated'}},
  {name: 'mesh_slide-flat-over-the-gap', demo: 'mesh_slide',  // resting on both blocks' corners
   actions: [['drag', 'e.axis0', [0.125, 3]]], stays: ([, y]) => y > 1.25,
   expect: {status: 'slid', contacts: 1, rounds: 2, hits: '7', relation: 'touching', touched: '7,8,10'}},

  // Points to ellipses: the ten starting points, one added, one moved, one removed; then three
  // points on a line (no ellipse: each part says why) and two more off it.
  {name: 'geometry-start', demo: 'geometry', actions: [],
   expect: {'enclose.status': 'optimal', 'inscribe.status': 'optimal', 'fit.status': 'converged', 'hull.faces': 10}},
  {name: 'geometry-click-adds-a-point', demo: 'geometry', actions: [['press', [5.5, 3.5]]],
   expect: {'enclose.status': 'optimal', 'inscribe.status': 'optimal', 'fit.status': 'converged'}, points: 11},
  {name: 'geometry-drag-a-point', demo: 'geometry', actions: [['drag', 'p2', [-0.5, 5]]],
   expect: {'enclose.status': 'optimal', 'inscribe.status': 'optimal'}, points: 11},
  {name: 'geometry-shift-click-removes', demo: 'geometry', actions: [['shift', [5.5, 3.5]]],
   expect: {'enclose.status': 'optimal', 'inscribe.status': 'optimal', 'fit.status': 'converged'}, points: 10},
  {name: 'geometry-collinear', demo: 'geometry',
   actions: [['click', 'geometry-clear'], ['press', [-3, -2]], ['press', [0, 0]], ['press', [3, 2]]],
   expect: {}, points: 3, refused: ['enclose', 'inscribe', 'fit']},
  {name: 'geometry-five-points', demo: 'geometry', actions: [['press', [0, 3]], ['press', [1, -2.5]]],
   expect: {'enclose.status': 'optimal', 'inscribe.status': 'optimal'}, points: 5},
];

// The mesh slide never ends inside a triangle (the library's relation at the end) nor beyond
// one (`stays`), and its path, replayed round by round, ends where the slide does.
function checkMeshSlide(s, {shown: a}) {
  if (a.status !== 'overlapping_at_start' && !['separated', 'touching'].includes(a.relation))
    fail(`${s.name}: ends ${a.relation} with triangle ${a['relation.triangle']}`);
  const last = a.path.slice(-2);
  if (last[0] !== a.end[0] || last[1] !== a.end[1]) fail(`${s.name}: the path ends at ${last}, the slide at ${a.end}`);
  if (s.stays && !s.stays(a.end)) fail(`${s.name}: ends at ${a.end}, not where ${s.stays}`);
}

// The geometry demo holds the expected points; every point lies in the enclosing ellipse (its
// form at most 1 + 1e-12 in doubles: the certificate itself is the library's, in exact
// arithmetic); parts listed in `refused` say why instead of answering.
function checkGeometry(s, {params, shown: a, verdict}) {
  if (s.points !== undefined && params.n !== s.points) fail(`${s.name}: ${params.n} points, expected ${s.points}`);
  for (const part of s.refused || [])
    if (a[part + '.error'] === undefined || a[part + '.status'] !== undefined) fail(`${s.name}: ${part} answered`);
  if (s.refused && verdict !== 'undecided') fail(`${s.name}: verdict ${verdict}`);
  if (a['enclose.status'] === undefined) return;
  const [cx, cy] = a['enclose.center'], [r0, r1] = a['enclose.radii'], t = a['enclose.angle'];
  for (let k = 0; k < params.n; k++) {
    const dx = params[`p${k}.x`] - cx, dy = params[`p${k}.y`] - cy;
    const u = (dx * Math.cos(t) + dy * Math.sin(t)) / r0, v = (-dx * Math.sin(t) + dy * Math.cos(t)) / r1;
    if (!(u * u + v * v <= 1 + 1e-12)) fail(`${s.name}: point ${k} outside the enclosing ellipse (${u * u + v * v})`);
  }
}

const results = [];
for (const s of scenarios) {
  for (const [kind, what, to] of s.actions) {
    if (kind === 'drag') await drag(s.demo, what, to);
    else if (kind === 'level') await testid('polygonal-level').fill(what);
    else if (kind === 'time') await testid('swept-time').fill(what);
    else if (kind === 'body') await testid('polygonal-body').selectOption(what);
    else if (kind === 'cover') await testid('polygonal-cover').setChecked(what);
    else if (kind === 'click') await testid(what).click();
    else if (kind === 'press') await press(s.demo, what);
    else if (kind === 'shift') await press(s.demo, what, true);
  }
  const shown = await readDemo(s.demo);
  for (const [key, want] of Object.entries(s.expect))
    if (shown.shown[key] !== want) fail(`${s.name}: ${key} is ${JSON.stringify(shown.shown[key])}, expected ${JSON.stringify(want)}`);
  if (s.demo === 'mesh_slide') checkMeshSlide(s, shown);
  if (s.demo === 'geometry') checkGeometry(s, shown);
  await page.locator('#' + s.demo).screenshot({path: join(out, s.name + '.png')});
  results.push({...s, ...shown});
  console.log(`${s.name}: ${shown.headline}`);
}

// ---- the native answers for the same inputs ---------------------------------------------

const native = JSON.parse(execFileSync(nativeProgram, {input: JSON.stringify(results.map((r) => ({demo: r.demo, params: r.params})))}));
let compared = 0, identical = 0, worst = 0;
function same(a, b, where) {
  if (Array.isArray(b)) {
    if (!Array.isArray(a) || a.length !== b.length) return fail(`${where}: page ${JSON.stringify(a)?.slice(0, 80)}, native length ${b.length}`);
    return b.forEach((v, i) => same(a[i], v, `${where}[${i}]`));
  }
  compared++;
  if (a === b) return identical++;
  if (typeof a === 'number' && typeof b === 'number') {
    const rel = Math.abs(a - b) / Math.max(1, Math.abs(a), Math.abs(b));
    worst = Math.max(worst, rel);
    if (rel <= TOLERANCE) return;
  }
  fail(`${where}: page ${JSON.stringify(a)}, native ${JSON.stringify(b)}`);
}
results.forEach((r, i) => {
  const keys = new Set([...Object.keys(r.shown), ...Object.keys(native[i])]);
  for (const key of keys) {
    const [a, b] = [r.shown[key], native[i][key]];
    if (STEP_COUNTS.has(key) && a > 0 && b > 0 && Math.abs(a - b) <= STEP_COUNT_TOLERANCE * b) continue;
    same(a, b, `${r.name}: ${key}`);
  }
});
console.log(`compared ${compared} values with the native library: ${identical} identical, ` +
            `largest relative difference ${worst.toExponential(2)}`);

// ---- time per frame -------------------------------------------------------------------

const timing = {};
for (const demo of ['ellipse_circle', 'segment_circle', 'polygonal', 'swept', 'relation', 'slide', 'mesh_slide', 'geometry']) {
  const query = await page.evaluate((d) => window.ellipsectDemo.time(d, 300), demo);
  const frame = await page.evaluate((d) => window.ellipsectDemo.time(d, 100, true), demo);
  timing[demo] = {query_ms: query, frame_ms: frame};
  console.log(`${demo}: query ${query.toFixed(4)} ms, frame (query + drawing) ${frame.toFixed(4)} ms`);
  if (!(query < budget(demo))) fail(`${demo}: ${query} ms per query, budget ${budget(demo)} ms`);
}

await page.screenshot({path: join(out, 'page.png'), fullPage: true});
for (const e of consoleErrors) fail('console: ' + e);
writeFileSync(join(out, 'results.json'), JSON.stringify({results, native, timing, consoleErrors, failures}, null, 1));
await browser.close();
server.close();
console.log(failures.length ? `${failures.length} failure(s)` : `all ${scenarios.length} scenarios passed (${Date.now() - started} ms)`);
process.exit(failures.length ? 1 : 0);
