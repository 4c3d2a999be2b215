// Browser test of the demo pages (index.html, 3d.html): headless Chromium drives every demo
// with the mouse and keyboard to scripted positions and values, reads the verdicts and numbers
// from the page and compares them with the native library's answers for the same inputs
// (web/tests/native_answers.cpp). The 3D page renders through WebGL in software (SwiftShader).
//
//   node web/tests/browser_test.mjs SITE_DIR NATIVE_ANSWERS OUT_DIR
//
// SITE_DIR: the built page (build/web/site); NATIVE_ANSWERS: the native program;
// OUT_DIR: screenshots (one per scenario and permalink, page.png for the 2D page) and results.json. Exit status 1 on
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
// the geometry demo's inscribed ellipse certifies its last centers in long double, which the
// wasm build computes in 128-bit software floating point, and its enclosing ellipse in
// rationals (Boost's, without GMP).
// motion3d: a rigid first contact and ten sampled overlaps.
// mesh_slide3d: the same replay over its 26 triangles.
const FRAME_BUDGET_MS = {mesh_slide: 3, geometry: 10, motion3d: 5, mesh_slide3d: 10};
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

const browser = await chromium.launch({executablePath: '/usr/bin/chromium',
                                       args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
                                              '--ignore-gpu-blocklist']});
const page = await browser.newPage({viewport: {width: 1100, height: 900}});
const consoleErrors = [];
page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
page.on('pageerror', (e) => consoleErrors.push(String(e)));

const started = Date.now();
const loadTimes = {};
// Opens a page of the site (path and hash) and waits until the library has answered every demo.
async function open(path) {
  const t0 = Date.now();
  await page.goto(url + path);
  await page.waitForSelector('[data-testid=status][data-ready=true]', {timeout: 30000});
  loadTimes[path] = Date.now() - t0;
  console.log(`${path} ready in ${loadTimes[path]} ms`);
}

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

// The 3D page (3d.html). `fill`: a value typed into a field (the test id demo-name); `drag3d`: a
// handle (or, with null, the view itself: an orbit, `moves` naming a handle whose place on
// screen must change) dragged by pixels; `check`: more conditions on what is shown.
const overlapsAt = (a, times) => times.map((t) => a['samples.overlap'][a['samples.times'].indexOf(t)]);
const scenarios3d = [
  {name: 'pair3d-start', demo: 'pair3d', actions: [],
   expect: {relation: 'separated', 'distance.status': 'separated', 'pw.status': 'ok', 'approach.status': 'ok'},
   check(r, bad) {  // F > 1 apart; the gradient by b's center is the normal, by a's its opposite
     const a = r.shown;
     if (!(a['pw.f'] > 1 && a.distance > 0)) bad(`F ${a['pw.f']}, distance ${a.distance}`);
     if (!(a['approach.distance'] > a.distance)) bad('closest approach along the centers shorter than the distance');
   }},
  {name: 'pair3d-orbit', demo: 'pair3d', actions: [['drag3d', null, [120, 0]]], moves: 'b.center',
   expect: {relation: 'separated'}},
  {name: 'pair3d-drag-a-center', demo: 'pair3d', actions: [['drag3d', 'a.center', [60, -20]]],
   check(r, bad) { if (r.params['a.cx'] === 0 && r.params['a.cy'] === 0 && r.params['a.cz'] === 0) bad('a did not move'); },
   expect: {}},
  {name: 'pair3d-overlapping', demo: 'pair3d',
   actions: [['fill', 'a.cx', 0], ['fill', 'a.cy', 0], ['fill', 'a.cz', 0], ['fill', 'b.cx', 2.5], ['fill', 'b.cy', 0.5], ['fill', 'b.cz', 0]],
   expect: {relation: 'overlapping', 'distance.status': 'overlapping'},
   check(r, bad) { if (!(r.shown['pw.f'] < 1 && r.shown.distance < 0)) bad(`F ${r.shown['pw.f']}, distance ${r.shown.distance}`); }},
  {name: 'pair3d-turn-sliders', demo: 'pair3d', actions: [['fill', 'b.cx', 3.5], ['fill', 'b.yaw', 90], ['fill', 'a.pitch', 0]],
   expect: {relation: 'overlapping'}, check(r, bad) { if (Math.abs(r.params['b.yaw'] - Math.PI / 2) > 1e-15) bad(`yaw ${r.params['b.yaw']}`); }},
  {name: 'pair3d-zero-radius', demo: 'pair3d', actions: [['fill', 'a.r1', 0]],
   expect: {error: 'a.radii[1]'}, check(r, bad) { if (r.verdict !== 'failed' || !r.headline.includes('a.radii[1]')) bad(r.headline); }},
  {name: 'pair3d-radius-restored', demo: 'pair3d', actions: [['fill', 'a.r1', 1.5]], expect: {'pw.status': 'ok'}},
  // The 2D toggle: the bodies' x, y, yaw, r0, r1 as ellipses, answered by the 2D functions
  // (2-vectors; the turn's gradient a number); the third dimension's fields hidden.
  {name: 'pair3d-2d', demo: 'pair3d', actions: [['click', 'pair3d-2d']], expect: {'distance.status': 'overlapping'},
   async check(r, bad) {
     if (r.params.dim !== 2 || r.shown['a.center'].length !== 2 || typeof r.shown['gradient.a.orientation'] !== 'number')
       bad(`dim ${r.params.dim}, a.center ${r.shown['a.center']}`);
     if (await testid('pair3d-a.cz').isVisible() || !(await testid('pair3d-a.cx').isVisible())) bad('the fields shown are not the 2D ones');
   }},
  {name: 'pair3d-2d-apart', demo: 'pair3d', actions: [['fill', 'b.cx', 6], ['fill', 'b.cy', 2]],
   expect: {relation: 'separated', 'distance.status': 'separated', 'pw.status': 'ok'},
   check(r, bad) {  // apart: F > 1; the gradient by b's center is the unit normal
     const a = r.shown, [gx, gy] = a['gradient.b.center'];
     if (!(a['pw.f'] > 1 && a.distance > 0)) bad(`F ${a['pw.f']}, distance ${a.distance}`);
     if (!(Math.abs(Math.hypot(gx, gy) - 1) < 1e-12)) bad(`|gradient| ${Math.hypot(gx, gy)}`);
   }},
  {name: 'pair3d-2d-drag', demo: 'pair3d', actions: [['drag3d', 'b.center', [-50, 30]]], expect: {},
   check(r, bad) { if (r.params['b.cx'] === 6 && r.params['b.cy'] === 2) bad('b did not move'); if (r.params['b.cz'] !== 0) bad(`b.cz ${r.params['b.cz']}`); }},
  {name: 'pair3d-2d-zero-radius', demo: 'pair3d', actions: [['fill', 'a.r1', 0]], expect: {error: 'a.radii[1]'}},
  {name: 'pair3d-back-to-3d', demo: 'pair3d', actions: [['fill', 'a.r1', 1.5], ['click', 'pair3d-2d']], expect: {'pw.status': 'ok'},
   check(r, bad) { if (r.params.dim !== 3 || r.shown['a.center'].length !== 3) bad(`dim ${r.params.dim}`); }},

  {name: 'motion3d-fast-spin', demo: 'motion3d', actions: [['click', 'motion3d-preset-fast-spin']],
   expect: {'contact.status': 'hit', 'sampling.verdict': 'missed'}},
  {name: 'motion3d-at-contact', demo: 'motion3d', actions: [['click', 'motion3d-to-contact']],
   expect: {'contact.status': 'hit', relation_t: 'touching'}},
  {name: 'motion3d-tumbling-needles', demo: 'motion3d', actions: [['click', 'motion3d-preset-tumbling-needles']],
   expect: {'contact.status': 'hit', 'sampling.verdict': 'late'},
   check(r, bad) {  // the first overlapping sample is after the contact, none before
     const a = r.shown, before = a['samples.times'].filter((t) => t < a['sampling.time']);
     if (!(a['sampling.time'] > a['contact.time'])) bad(`sampled ${a['sampling.time']}, contact ${a['contact.time']}`);
     if (overlapsAt(a, before).some((x) => x)) bad('an earlier sample overlaps');
   }},
  {name: 'motion3d-time-slider', demo: 'motion3d', actions: [['fill', 'time', 0.6]],
   check(r, bad) { if (r.params.t !== 0.6 * r.params.t_max) bad(`t ${r.params.t}`); },
   expect: {'contact.status': 'hit'}},
  // Linear motion: Eberly's reduced frame beside; at the contact time the reduced body's point
  // nearest the origin is on the unit sphere.
  {name: 'motion3d-linear', demo: 'motion3d', actions: [['click', 'motion3d-preset-linear']],
   expect: {motion: 'linear', 'contact.status': 'hit', 'sampling.verdict': 'late', relation_t: 'separated'},
   async check(r, bad) {
     if (!(Math.hypot(...r.shown['reduced.p']) > 1)) bad(`|P| ${Math.hypot(...r.shown['reduced.p'])} at t = 0, apart`);
     if (!(await testid('motion3d-reduced').isVisible())) bad('no reduced frame');
   }},
  {name: 'motion3d-linear-at-contact', demo: 'motion3d', actions: [['click', 'motion3d-to-contact']],
   expect: {motion: 'linear', relation_t: 'touching'},
   check(r, bad) { if (!(Math.abs(Math.hypot(...r.shown['reduced.p']) - 1) < 1e-9)) bad(`|P| ${Math.hypot(...r.shown['reduced.p'])} at contact`); }},
  {name: 'motion3d-linear-drag', demo: 'motion3d', actions: [['drag3d', 'b.center', [0, -30]]], expect: {motion: 'linear'}},
  {name: 'motion3d-grazing', demo: 'motion3d', actions: [['click', 'motion3d-preset-grazing']],
   expect: {'contact.status': 'hit', 'sampling.verdict': 'missed', motion: 'rigid'},
   async check(r, bad) { if (await testid('motion3d-reduced').isVisible()) bad('a reduced frame for rigid motion'); }},
  {name: 'motion3d-drag-b', demo: 'motion3d', actions: [['drag3d', 'b.center', [0, 40]]],
   check(r, bad) { if (r.params['b.cx'] === 0.6 && r.params['b.cy'] === 2.05 && r.params['b.cz'] === 0) bad('b did not move'); },
   expect: {}},
  {name: 'motion3d-negative-growth', demo: 'motion3d', actions: [['fill', 'a.g', -1]],
   expect: {error: 'a.growth'}, check(r, bad) { if (r.verdict !== 'failed') bad(r.headline); }},
  {name: 'motion3d-negative-window', demo: 'motion3d', actions: [['fill', 'a.g', 0], ['fill', 't_max', -1]],
   expect: {error: 't_max'}},
  {name: 'motion3d-window-restored', demo: 'motion3d', actions: [['fill', 't_max', 2]], expect: {}},

  // The 3D level's triangles: 0, 1 floor; 2 .. 11 the box (8, 9 its face towards -x); 12, 13 the
  // ramp; 14 .. 23 the ledge; 24, 25 the wall.
  {name: 'mesh_slide3d-along-the-box', demo: 'mesh_slide3d', actions: [], check: checkSlide3d,
   expect: {status: 'slid', contacts: 1, rounds: 2, hits: '8', relation: 'touching', touched: '1,8'}},
  {name: 'mesh_slide3d-into-the-wall', demo: 'mesh_slide3d', actions: [['fill', 'tx', 7], ['fill', 'ty', 0]], check: checkSlide3d,
   expect: {status: 'slid', contacts: 1, hits: '24', relation: 'touching', touched: '0,24'}},
  {name: 'mesh_slide3d-up-the-ramp', demo: 'mesh_slide3d', actions: [['fill', 'e.cy', -3.5], ['fill', 'ty', -3.5], ['fill', 'tx', 0]],
   check: checkSlide3d, expect: {status: 'slid', contacts: 1, hits: '13', relation: 'separated'}},
  {name: 'mesh_slide3d-into-the-floor', demo: 'mesh_slide3d',
   actions: [['fill', 'e.cy', 0], ['fill', 'tx', -2], ['fill', 'ty', 0], ['fill', 'tz', -1]], check: checkSlide3d,
   expect: {status: 'slid', contacts: 0, relation: 'touching', touched: '1'}},
  {name: 'mesh_slide3d-drag-target', demo: 'mesh_slide3d', actions: [['drag3d', 'target', [160, -60]]], check: checkSlide3d, expect: {}},
  {name: 'mesh_slide3d-zero-radius', demo: 'mesh_slide3d', actions: [['fill', 'e.r2', 0]], expect: {error: 'e.radii[2]'}},
  {name: 'mesh_slide3d-radius-restored', demo: 'mesh_slide3d', actions: [['fill', 'e.r2', 0.5]], check: checkSlide3d, expect: {}},

  // The live packing: a wrong field; a few collisions at one a frame, then three single steps
  // (the state compared with the native run to the same count); runs to jamming in 2D and 3D,
  // checked against the native run to jamming (the same start; the trajectories part after
  // many collisions, so the density within PACKING_DENSITY) and the page's final bodies
  // checked for overlaps by the native library.
  {name: 'packing-bad-size', demo: 'packing', actions: [['fill', 'n', 5], ['click', 'packing-start']], expect: {error: 'n'}},
  {name: 'packing-steps', demo: 'packing',
   actions: [['fill', 'n', 60], ['fill', 'dim', 2], ['fill', 'aspect', 1.6], ['fill', 'rate', 0.1], ['fill', 'pressure', 1000],
             ['fill', 'seed', 1], ['fill', 'per-slice', 1], ['click', 'packing-start'], ['click', 'packing-pause'],
             ['click', 'packing-step'], ['click', 'packing-step'], ['click', 'packing-step']],
   expect: {status: 'compressing'}, native: (r) => ({...r.params, collisions: r.shown.collisions}),
   check(r, bad) { if (!(r.shown.collisions >= 3 && r.shown.collisions < 200)) bad(`${r.shown.collisions} collisions`); }},
  {name: 'packing-jam-2d', demo: 'packing', actions: [['fill', 'per-slice', 4000], ['click', 'packing-start'], ['jammed']],
   expect: {status: 'jammed', overlapping: 0}, native: null, check: checkJammed},
  {name: 'packing-jam-3d', demo: 'packing',
   actions: [['fill', 'dim', 3], ['fill', 'n', 64], ['fill', 'aspect', 1.4], ['fill', 'rate', 0.3], ['click', 'packing-start'], ['jammed']],
   expect: {status: 'jammed', overlapping: 0}, native: null, check: checkJammed},
];

// The slide never ends inside the mesh, and its path, replayed round by round, ends where it does.
function checkSlide3d({shown: a}, bad) {
  if (!['separated', 'touching'].includes(a.relation)) bad(`ends ${a.relation} with triangle ${a['relation.triangle']}`);
  if (a.path.slice(-3).some((x, k) => x !== a.end[k])) bad(`the path ends at ${a.path.slice(-3)}, the slide at ${a.end}`);
}

const PACKING_DENSITY = 0.03;
// The packing's library work runs in a worker, so no frame of the page waits for it; the
// view lags it by one slice (15 ms and a chunk of collisions by design), which must stay
// within this for 95% of the slices (wall clock: a loaded machine stretches a few).
const LIBRARY_MS_PER_SLICE = 50;
function checkJammed(r, bad) {
  const a = r.shown, [reference] = JSON.parse(execFileSync(nativeProgram, {input: JSON.stringify([{demo: 'packing', params: r.params}])}));
  if (!(a.pressure >= r.params.pressure)) bad(`pressure ${a.pressure}`);
  if (!(Math.abs(a.density - reference.density) < PACKING_DENSITY)) bad(`density ${a.density}, native ${reference.density}`);
  const bodies = {dim: r.params.dim, n: r.params.n};
  for (const key of ['centers', 'axes', 'radii', 'box']) a[key].forEach((v, k) => { bodies[`${key}.${k}`] = v; });
  const [check] = JSON.parse(execFileSync(nativeProgram, {input: JSON.stringify([{demo: 'packing_check', params: bodies}])}));
  if (check.overlapping !== 0) bad(`${check.overlapping} pairs of the page's bodies overlap (native classify)`);
  const slices = [...r.slices].sort((x, y) => x - y), p95 = slices[Math.floor(0.95 * (slices.length - 1))];
  if (!(p95 < LIBRARY_MS_PER_SLICE)) bad(`a twentieth of the slices of library work took more than ${p95} ms`);
  console.log(`  density ${a.density} (native ${reference.density}), ${a.collisions} collisions (native ${reference.collisions}), ` +
              `${slices.length} slices of library work: median ${slices[slices.length >> 1].toFixed(1)} ms, ` +
              `95th percentile ${p95.toFixed(1)} ms, most ${slices.at(-1).toFixed(1)} ms`);
}

// Each 3D demo's permalink (after the scenarios above) opens the page with the same inputs, and
// the page's location is the permalink of the demo changed last.
async function checkPermalinks() {
  const hash = await page.evaluate(() => location.hash), demos = ['pair3d', 'motion3d', 'mesh_slide3d', 'packing'];
  const links = {}, params = {};
  for (const demo of demos) {
    links[demo] = await testid(demo + '-permalink').getAttribute('href');
    params[demo] = await testid(demo + '-params').textContent();
  }
  if (hash !== links.packing) fail(`location ${hash}, the last demo changed links ${links.packing}`);
  for (const demo of demos) {
    await page.goto('about:blank');  // a load, not a change of hash
    await open('3d.html' + links[demo]);
    const restored = await testid(demo + '-params').textContent();
    if (restored !== params[demo]) fail(`${demo} permalink: ${restored}, expected ${params[demo]}`);
    await page.locator('#' + demo).screenshot({path: join(out, demo + '-permalink.png')});
  }
}

// A drag on a 3D view: from a handle (or, for an orbit, from a point of the view away from
// the bodies) by (dx, dy) pixels.
async function drag3d(demo, handle, [dx, dy]) {
  await page.locator('#' + demo + ' canvas.view').scrollIntoViewIfNeeded();
  const from = handle ? await page.evaluate(([d, h]) => window.ellipsectDemo.handleClient(d, h), [demo, handle])
    : await page.locator('#' + demo + ' canvas.view').evaluate((c) => { const r = c.getBoundingClientRect(); return [r.left + 30, r.bottom - 30]; });
  await page.mouse.move(from[0], from[1]);
  await page.mouse.down();
  await page.mouse.move(from[0] + dx, from[1] + dy, {steps: 6});
  await page.mouse.up();
}

const results = [];
async function run(list) {
  for (const s of list) {
    const before = s.moves ? await page.evaluate(([d, h]) => window.ellipsectDemo.handleClient(d, h), [s.demo, s.moves]) : null;
    for (const [kind, what, to] of s.actions) {
      if (kind === 'drag') await drag(s.demo, what, to);
      else if (kind === 'level') await testid('polygonal-level').fill(what);
      else if (kind === 'time') await testid('swept-time').fill(what);
      else if (kind === 'body') await testid('polygonal-body').selectOption(what);
      else if (kind === 'cover') await testid('polygonal-cover').setChecked(what);
      else if (kind === 'click') await testid(what).click();
      else if (kind === 'press') await press(s.demo, what);
      else if (kind === 'shift') await press(s.demo, what, true);
      else if (kind === 'fill') await testid(`${s.demo}-${what}`).fill(String(to));
      else if (kind === 'drag3d') await drag3d(s.demo, what, to);
      else if (kind === 'jammed') await page.waitForSelector('[data-testid=packing-headline][data-verdict=no_collision]', {timeout: 240000});
      // The packing's worker has answered every message and the page has drawn the last one.
      if (s.demo === 'packing') await page.waitForFunction(() => { const d = window.ellipsectDemo.demos.packing; return d.pending === 0 && d.latest === null; });
    }
    const shown = await readDemo(s.demo);
    if (s.demo === 'packing') shown.slices = await page.evaluate(() => window.ellipsectDemo.demos.packing.slices);
    for (const [key, want] of Object.entries(s.expect))
      if (shown.shown[key] !== want) fail(`${s.name}: ${key} is ${JSON.stringify(shown.shown[key])}, expected ${JSON.stringify(want)}`);
    if (s.demo === 'mesh_slide') checkMeshSlide(s, shown);
    if (s.demo === 'geometry') checkGeometry(s, shown);
    if (s.check) await s.check(shown, (msg) => fail(`${s.name}: ${msg}`));
    if (s.moves) {  // an orbit: the camera turned (the handle is elsewhere on screen), nothing else changed
      const after = await page.evaluate(([d, h]) => window.ellipsectDemo.handleClient(d, h), [s.demo, s.moves]);
      if (Math.hypot(after[0] - before[0], after[1] - before[1]) < 5) fail(`${s.name}: the view did not turn`);
    }
    await page.locator('#' + s.demo).screenshot({path: join(out, s.name + '.png')});
    results.push({...s, ...shown});
    console.log(`${s.name}: ${shown.headline}`);
  }
}

// The mean time of a query and of a frame (query, drawing, read-outs) of each demo over
// `frames` frames; the query within its budget.
const timing = {};
async function time(demos, frames = 100) {
  for (const demo of demos) {
    const query = await page.evaluate((d) => window.ellipsectDemo.time(d, 300), demo);
    const frame = await page.evaluate(([d, n]) => window.ellipsectDemo.time(d, n, true), [demo, frames]);
    timing[demo] = {query_ms: query, frame_ms: frame};
    console.log(`${demo}: query ${query.toFixed(4)} ms, frame (query + drawing) ${frame.toFixed(4)} ms`);
    if (!(query < budget(demo))) fail(`${demo}: ${query} ms per query, budget ${budget(demo)} ms`);
  }
}

await open('');
await run(scenarios);
await time(['ellipse_circle', 'segment_circle', 'polygonal', 'swept', 'relation', 'slide', 'mesh_slide', 'geometry']);
await page.screenshot({path: join(out, 'page.png'), fullPage: true});

await open('3d.html');
await run(scenarios3d);
await time(['pair3d', 'motion3d', 'mesh_slide3d'], 10);  // software WebGL: slow frames
// No update of a 3D demo, through every scenario and timing above, waited longer than this for
// the library on the page's thread (the packing's work is in its worker).
const FRAME_LIBRARY_MS = 50;
for (const demo of ['pair3d', 'motion3d', 'mesh_slide3d']) {
  const most = await page.evaluate((d) => window.ellipsectDemo.maxQueryMs(d), demo);
  console.log(`${demo}: the longest wait of a frame for the library ${most.toFixed(2)} ms`);
  if (!(most < FRAME_LIBRARY_MS)) fail(`${demo}: a frame waited ${most} ms for the library`);
}
await checkPermalinks();

// ---- the native answers for the same inputs ---------------------------------------------

// `native`: the inputs of the native answer to compare with (null: none, its check compares).
const compared_results = results.filter((r) => r.native !== null);
const native = JSON.parse(execFileSync(nativeProgram, {input: JSON.stringify(compared_results.map((r) => ({demo: r.demo, params: r.native ? r.native(r) : r.params})))}));
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
compared_results.forEach((r, i) => {
  const keys = new Set([...Object.keys(r.shown), ...Object.keys(native[i])]);
  for (const key of keys) {
    const [a, b] = [r.shown[key], native[i][key]];
    if (STEP_COUNTS.has(key) && a > 0 && b > 0 && Math.abs(a - b) <= STEP_COUNT_TOLERANCE * b) continue;
    same(a, b, `${r.name}: ${key}`);
  }
});
console.log(`compared ${compared} values with the native library: ${identical} identical, ` +
            `largest relative difference ${worst.toExponential(2)}`);

for (const e of consoleErrors) fail('console: ' + e);
writeFileSync(join(out, 'results.json'), JSON.stringify({results, native, timing, loadTimes, consoleErrors, failures}, null, 1));
await browser.close();
server.close();
console.log(failures.length ? `${failures.length} failure(s)` : `all ${results.length} scenarios passed (${Date.now() - started} ms)`);
process.exit(failures.length ? 1 : 0);
