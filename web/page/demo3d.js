// The 3D demos: a WebGL view (three.js) with orbit, zoom and draggable handles, fields and
// sliders for the inputs, and the read-outs. Every answer comes from the library through
// Module.answer(demo, params) (web/src/answers.hpp); this file only draws and converts.
import * as THREE from 'three';
import {OrbitControls} from './three/OrbitControls.js';
import {BLUE, GREEN, GREY, ORANGE, RED, format, ready, renderAnswer, showTimes} from './common.js';

const SNAP = 1 / 16;  // dragged coordinates snap to this grid (exact binary fractions)
const snap = (v) => Math.round(v / SNAP) * SNAP;
const DEGREE = Math.PI / 180;

let Module = null;

// ---- the view ---------------------------------------------------------------------------

const unitSphere = new THREE.SphereGeometry(1, 48, 24);

// A scene with z up, a grid in the plane z = 0 (1 unit apart), orbit and zoom (left drag,
// wheel), and handles: small spheres drawn on top that a drag moves in the plane through
// them facing the camera (handle.set(point), the point snapped to SNAP).
class View3D {
  constructor(canvas, onDrag) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({canvas, antialias: true, preserveDrawingBuffer: true});
    this.renderer.setSize(canvas.width, canvas.height, false);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color('#fff');
    this.camera = new THREE.PerspectiveCamera(40, canvas.width / canvas.height, 0.1, 500);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(8, -13, 9);
    this.scene.add(new THREE.AmbientLight(0xffffff, 1.4));
    const sun = new THREE.DirectionalLight(0xffffff, 2.2);
    sun.position.set(4, -6, 10);
    this.scene.add(sun);
    const grid = new THREE.GridHelper(16, 16, 0xbbbbbb, 0xe4e4e4);
    grid.rotation.x = Math.PI / 2;
    this.scene.add(grid, new THREE.AxesHelper(1));
    this.items = new THREE.Group();
    this.scene.add(this.items);
    this.handles = [];
    this.onDrag = onDrag;
    this.drag = null;
    this.raycaster = new THREE.Raycaster();
    // Before the orbit controls' own listener: a press on a handle is a drag, not an orbit.
    canvas.addEventListener('pointerdown', (ev) => this.grab(ev), {capture: true});
    canvas.addEventListener('pointermove', (ev) => this.move(ev));
    for (const end of ['pointerup', 'pointercancel']) canvas.addEventListener(end, () => { this.drag = null; });
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.addEventListener('change', () => this.render());
  }
  ray(ev) {
    const r = this.canvas.getBoundingClientRect();
    this.raycaster.setFromCamera(new THREE.Vector2((ev.clientX - r.left) / r.width * 2 - 1,
                                                   1 - (ev.clientY - r.top) / r.height * 2), this.camera);
    return this.raycaster.ray;
  }
  grab(ev) {
    this.ray(ev);
    const hit = this.raycaster.intersectObjects(this.handles.map((h) => h.object))[0];
    if (!hit) return;
    ev.stopImmediatePropagation();
    const h = this.handles.find((x) => x.object === hit.object);
    const facing = this.camera.getWorldDirection(new THREE.Vector3());
    this.drag = {handle: h, plane: new THREE.Plane().setFromNormalAndCoplanarPoint(facing, h.object.position)};
    this.canvas.setPointerCapture(ev.pointerId);
  }
  move(ev) {
    if (!this.drag) return;
    const p = this.ray(ev).intersectPlane(this.drag.plane, new THREE.Vector3());
    if (!p) return;
    this.drag.handle.set([snap(p.x), snap(p.y), snap(p.z)]);
    this.onDrag();
  }
  // Client coordinates of a world point (for tests and tools that drive the page).
  client(p) {
    const v = new THREE.Vector3(...p).project(this.camera), r = this.canvas.getBoundingClientRect();
    return [r.left + (v.x + 1) / 2 * r.width, r.top + (1 - v.y) / 2 * r.height];
  }
  clear() {
    for (const o of this.items.children) {
      o.traverse((x) => {
        if (x.material) x.material.dispose();
        if (x.userData.ownsGeometry) x.geometry.dispose();
      });
    }
    this.items.clear();
  }
  add(o) { this.items.add(o); return o; }
  // A body {center, axes (column-major), radii} as the library stored it.
  ellipsoid(body, color, {opacity = 1, wire = false} = {}) {
    const material = new THREE.MeshStandardMaterial({color, roughness: 0.6, wireframe: wire, transparent: opacity < 1,
                                                     opacity, depthWrite: opacity === 1});
    const mesh = new THREE.Mesh(unitSphere, material), [a, r, c] = [body.axes, body.radii, body.center];
    mesh.matrixAutoUpdate = false;
    mesh.matrix.set(a[0] * r[0], a[3] * r[1], a[6] * r[2], c[0],
                    a[1] * r[0], a[4] * r[1], a[7] * r[2], c[1],
                    a[2] * r[0], a[5] * r[1], a[8] * r[2], c[2],
                    0, 0, 0, 1);
    return this.add(mesh);
  }
  point(p, color, radius = 0.08) {
    if (!p.every(Number.isFinite)) return;
    const m = this.add(new THREE.Mesh(unitSphere, new THREE.MeshBasicMaterial({color, depthTest: false})));
    m.position.set(...p);
    m.scale.setScalar(radius);
    m.renderOrder = 2;
  }
  segment(p, q, color) {
    if (![...p, ...q].every(Number.isFinite)) return;
    const g = new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(...p), new THREE.Vector3(...q)]);
    const line = this.add(new THREE.Line(g, new THREE.LineBasicMaterial({color, depthTest: false})));
    line.renderOrder = 2;
    line.userData.ownsGeometry = true;
  }
  // An arrow from `from` along v (drawn at its length times `scale`).
  arrow(from, v, color, scale = 1) {
    const length = Math.hypot(...v) * scale;
    if (!(length > 0) || !from.every(Number.isFinite)) return;
    const dir = new THREE.Vector3(...v).normalize();
    const a = this.add(new THREE.ArrowHelper(dir, new THREE.Vector3(...from), length, color,
                                             Math.min(0.3, 0.4 * length), Math.min(0.15, 0.2 * length)));
    a.traverse((x) => { if (x.material) { x.material.depthTest = false; x.renderOrder = 3; } });
  }
  setHandles(handles) {
    for (const h of this.handles) { h.object.material.dispose(); this.scene.remove(h.object); }
    this.handles = handles.map((h) => {
      const object = new THREE.Mesh(unitSphere, new THREE.MeshBasicMaterial({color: '#333', depthTest: false,
                                                                              transparent: true, opacity: 0.8}));
      object.position.set(...h.at());
      object.scale.setScalar(0.14);
      object.renderOrder = 4;
      this.scene.add(object);
      return {...h, object};
    });
  }
  render() { this.renderer.render(this.scene, this.camera); }
}

// ---- the demos --------------------------------------------------------------------------

// A body of an answer: name.center, name.axes, name.radii (drawn, not tabulated).
const bodyOf = (a, name) => ({center: a[name + '.center'], axes: a[name + '.axes'], radii: a[name + '.radii']});
const bodyKeys = (...names) => names.map((n) => n + '.');

// A demo: its state `s` (the library's parameter names and values, which is also its
// permalink: #id?name=value&...), fields bound to names of s, handles moving centers,
// draw(view, answer) and headline(answer) -> [text, class]. Keys starting with a `hidden`
// prefix are drawn, not tabulated.
class Demo3D {
  constructor(id, spec) {
    Object.assign(this, spec);
    this.id = id;
    this.section = document.getElementById(id);
    this.table = this.section.querySelector('.readout');
    this.view = new View3D(this.section.querySelector('canvas.view'), () => this.update());
    this.fields = [];
  }
  params() { return {...this.s}; }
  query() { return Module.answer(this.id, this.params()); }
  // A number field (or, with {degrees: true}, a slider in degrees) for each name, in `where`.
  bind(where, names, {degrees = false, step = 'any', label = (n) => n.split('.').pop()} = {}) {
    for (const name of names) {
      const l = document.createElement('label'), input = document.createElement('input');
      input.type = degrees ? 'range' : 'number';
      Object.assign(input, degrees ? {min: -180, max: 180, step: 1} : {step});
      input.dataset.testid = `${this.id}-${name}`;
      input.addEventListener('input', () => {
        this.s[name] = degrees ? input.valueAsNumber * DEGREE : input.valueAsNumber;
        this.update();
      });
      l.append(label(name) + ' ', input);
      where.append(l);
      this.fields.push({name, input, degrees});
    }
  }
  // The fields show the state (but the one being typed in).
  sync() {
    for (const {name, input, degrees} of this.fields)
      if (input !== document.activeElement || degrees) input.value = degrees ? Math.round(this.s[name] / DEGREE) : this.s[name];
  }
  permalink() { return '#' + this.id + '?' + new URLSearchParams(Object.entries(this.s).map(([k, v]) => [k, String(v)])); }
  // The state of a permalink naming this demo (location.hash), if any.
  restore(hash) {
    if (!hash.startsWith('#' + this.id + '?')) return false;
    for (const [k, v] of new URLSearchParams(hash.slice(this.id.length + 2))) if (k in this.s) this.s[k] = Number(v);
    return true;
  }
  // Handles on the centers named prefix.cx, prefix.cy, prefix.cz (`flat`: in the plane z = 0,
  // moving cx and cy alone).
  centerHandle(prefix, flat = false) {
    const s = this.s, names = ['cx', 'cy', 'cz'].map((k) => prefix + '.' + k);
    if (flat) return {name: prefix + '.center', at: () => [s[names[0]], s[names[1]], 0], set: (p) => { s[names[0]] = p[0]; s[names[1]] = p[1]; }};
    return {name: prefix + '.center', at: () => names.map((n) => s[n]), set: (p) => names.forEach((n, i) => { s[n] = p[i]; })};
  }
  update({user = true} = {}) {
    const t0 = performance.now();
    const answer = this.query();
    const t1 = performance.now();
    this.maxQueryMs = Math.max(this.maxQueryMs ?? 0, t1 - t0);  // the most a frame waited for the library
    this.answer = answer;
    this.sync();
    this.view.clear();
    this.view.setHandles(this.handles());
    if (answer.error === undefined) this.draw(this.view, answer);
    this.view.render();
    renderAnswer(this, answer, 3);
    const link = this.section.querySelector('.permalink');
    link.href = this.permalink();
    if (user) history.replaceState(null, '', this.permalink());
    showTimes(t1 - t0, performance.now() - t0);
  }
}

const body = (prefix, c, angles, radii) => ({
  [prefix + '.cx']: c[0], [prefix + '.cy']: c[1], [prefix + '.cz']: c[2],
  [prefix + '.yaw']: angles[0] * DEGREE, [prefix + '.pitch']: angles[1] * DEGREE, [prefix + '.roll']: angles[2] * DEGREE,
  [prefix + '.r0']: radii[0], [prefix + '.r1']: radii[1], [prefix + '.r2']: radii[2]});
const SHAPE = ['cx', 'cy', 'cz', 'r0', 'r1', 'r2'], TURN = ['yaw', 'pitch', 'roll'];

// The fields of bodies a and b: center and radii, the turn as three sliders.
function bindBodies(demo) {
  for (const prefix of ['a', 'b']) {
    const where = demo.section.querySelector(`.body-${prefix}`);
    demo.bind(where, SHAPE.map((k) => prefix + '.' + k));
    demo.bind(where, TURN.map((k) => prefix + '.' + k), {degrees: true});
  }
}

// A 2D answer's point or body in the plane z = 0 (a body as a thin disc); 3D ones unchanged.
const lift = (p) => (p && p.length === 2 ? [p[0], p[1], 0] : p);
const liftBody = (b) => (b.center.length === 3 ? b : {center: lift(b.center), radii: [b.radii[0], b.radii[1], 0.02],
                                                      axes: [b.axes[0], b.axes[1], 0, b.axes[2], b.axes[3], 0, 0, 0, 1]});
// The fields that a 2D body (center x, y, radii r0, r1, turned by yaw) does not have.
const NOT_2D = ['cz', 'r2', 'pitch', 'roll'];

// Two ellipsoids (or, with the toggle, two ellipses in the plane z = 0): relation, signed
// distance, Perram-Wertheim F and the gradient.
function pairDemo() {
  const demo = new Demo3D('pair3d', {
    s: {dim: 3, ...body('a', [0, 0, 0], [20, 10, 0], [3, 1.5, 1]), ...body('b', [4, 1.5, 1], [-30, 25, 0], [2, 1, 0.75])},
    hidden: bodyKeys('a', 'b'),
    handles: () => [demo.centerHandle('a', demo.s.dim === 2), demo.centerHandle('b', demo.s.dim === 2)],
    draw(v, r) {
      const apart = r.relation === 'separated' || r.relation === 'touching';
      v.ellipsoid(liftBody(bodyOf(r, 'a')), apart ? BLUE : RED, {opacity: 0.45});
      v.ellipsoid(liftBody(bodyOf(r, 'b')), apart ? ORANGE : RED, {opacity: 0.45});
      const [pa, pb] = [lift(r.point_a), lift(r.point_b)];
      v.segment(pa, pb, '#222');
      v.point(pa, BLUE);
      v.point(pb, ORANGE);
      v.arrow(pa, lift(r.normal), RED);
      v.arrow(lift(r['a.center']), lift(r['gradient.a.center']), GREEN);
      v.arrow(lift(r['b.center']), lift(r['gradient.b.center']), GREEN);
      if (r['approach.point']) v.point(lift(r['approach.point']), GREY, 0.06);
    },
    headline(r) {
      const d = r.relation === 'separated' ? `${format(r.distance)} apart` : `penetration depth ${format(-r.distance)}`;
      return [`${r.relation.replaceAll('_', ' ')}: ${d}; Perram–Wertheim F = ${format(r['pw.f'])} (μ = ${format(r['pw.mu'])}).`,
              r.relation === 'separated' ? 'no_collision' : 'collision'];
    },
  });
  bindBodies(demo);
  // The 2D toggle: the same fields less the third dimension's, the camera looking down on z = 0.
  const flat = demo.section.querySelector('[data-testid=pair3d-2d]');
  flat.addEventListener('change', () => {
    demo.s.dim = flat.checked ? 2 : 3;
    demo.lookAt(demo.s.dim);
    demo.update();
  });
  demo.lookAt = (dim) => {
    const v = demo.view;
    v.camera.position.set(...(dim === 2 ? [1.5, 0.2, 16] : [8, -13, 9]));
    v.controls.target.set(dim === 2 ? 1.5 : 0, dim === 2 ? 0.7 : 0, 0);
    v.controls.update();
  };
  const sync = demo.sync.bind(demo);
  demo.sync = () => {
    sync();
    flat.checked = demo.s.dim === 2;
    for (const {name, input} of demo.fields) input.parentElement.hidden = demo.s.dim === 2 && NOT_2D.includes(name.split('.').pop());
  };
  return demo;
}

// The presets of the motion demo: a long needle spinning fast past a still one (the samples
// miss it), two needles tumbling towards each other (reported late), a ball passing a growing
// one, overlapping it only between two samples (missed).
const MOTION_PRESETS = {
  'fast spin': {...body('a', [-3.5, 0, 0], [0, 0, 0], [3, 0.2, 0.2]), ...body('b', [3, 0, 0], [0, 0, 0], [3, 0.2, 0.2]),
                'a.vx': 1, 'a.vy': 0, 'a.vz': 0, 'a.wx': 0, 'a.wy': 0, 'a.wz': 20, 'a.g': 0,
                'b.vx': 0, 'b.vy': 0, 'b.vz': 0, 'b.wx': 0, 'b.wy': 0, 'b.wz': 0, 'b.g': 0, t_max: 2, t: 0},
  'tumbling needles': {...body('a', [-5, 0, 0], [0, 0, 0], [2, 0.15, 0.15]), ...body('b', [5, 0.5, 0], [90, 0, 0], [2, 0.15, 0.15]),
                       'a.vx': 2, 'a.vy': 0, 'a.vz': 0, 'a.wx': 3, 'a.wy': 0, 'a.wz': 2, 'a.g': 0,
                       'b.vx': -2, 'b.vy': 0, 'b.vz': 0, 'b.wx': 0, 'b.wy': 2, 'b.wz': 3, 'b.g': 0, t_max: 4, t: 0},
  // No spin, no growth: first_contact answers by Eberly's translational method, and the
  // reduced frame is drawn beside (ten samples report the contact late).
  linear: {...body('a', [-4, 0, 0], [17, 0, 0], [2, 1, 0.6]), ...body('b', [4, 1, 0.5], [-29, 23, 0], [2, 1, 0.75]),
           'a.vx': 2, 'a.vy': 0, 'a.vz': 0, 'a.wx': 0, 'a.wy': 0, 'a.wz': 0, 'a.g': 0,
           'b.vx': -1, 'b.vy': 0, 'b.vz': 0, 'b.wx': 0, 'b.wy': 0, 'b.wz': 0, 'b.g': 0, t_max: 4, t: 0},
  grazing: {...body('a', [-6, 0, 0], [0, 0, 0], [1, 1, 1]), ...body('b', [0.6, 2.05, 0], [0, 0, 0], [1, 1, 1]),
            'a.vx': 6, 'a.vy': 0, 'a.vz': 0, 'a.wx': 0, 'a.wy': 0, 'a.wz': 0, 'a.g': 0,
            'b.vx': 0, 'b.vy': 0, 'b.vz': 0, 'b.wx': 0, 'b.wy': 0, 'b.wz': 0, 'b.g': 0.06, t_max: 2, t: 0},
};

// Rigid motion with growth: the certified first contact, the bodies at the slider's time and
// at contact, and the ten samples of a sampling CCD beside it; for linear motion, the seed's
// reduced frame at the slider's time beside that.
function motionDemo() {
  const sec = document.getElementById('motion3d');
  const strip = sec.querySelector('canvas.samples'), time = sec.querySelector('[data-testid=motion3d-time]');
  const reduced = new View3D(sec.querySelector('canvas.reduced'), () => {});
  const reducedNote = sec.querySelector('[data-testid=motion3d-reduced-note]');
  const demo = new Demo3D('motion3d', {
    s: {...MOTION_PRESETS['fast spin']},
    hidden: ['samples.', ...bodyKeys('a', 'b', 'a_t', 'b_t', 'a_c', 'b_c')],
    handles: () => [demo.centerHandle('a'), demo.centerHandle('b')],
    draw(v, r) {
      const apart = r.relation_t === 'separated' || r.relation_t === 'touching';
      v.ellipsoid(bodyOf(r, 'a'), BLUE, {opacity: 0.15});
      v.ellipsoid(bodyOf(r, 'b'), ORANGE, {opacity: 0.15});
      for (const k of ['a', 'b']) v.arrow(r[k + '.center'], ['vx', 'vy', 'vz'].map((c) => this.s[k + '.' + c]), GREY);
      if (r['a_c.center']) {
        v.ellipsoid(bodyOf(r, 'a_c'), '#777', {wire: true});
        v.ellipsoid(bodyOf(r, 'b_c'), '#777', {wire: true});
        v.point(r['contact.point'], RED, 0.1);
        v.arrow(r['contact.point'], r['contact.normal'], RED);
      }
      v.ellipsoid(bodyOf(r, 'a_t'), apart ? BLUE : RED);
      v.ellipsoid(bodyOf(r, 'b_t'), apart ? ORANGE : RED);
      drawSamples(r);
      drawReduced(r);
    },
    headline(r) {
      const text = {hit: `First contact at t = ${format(r['contact.time'])}`, touching_at_start: 'Touching at t = 0',
                    overlapping_at_start: 'Overlapping at t = 0',
                    no_contact_in_window: `No contact for t in [0, ${format(this.s.t_max)}]`}[r['contact.status']] ||
                   r['contact.status'];
      const sampling = {missed: 'ten samples miss it', agrees: 'ten samples agree',
                        late: `ten samples report it late, at t = ${format(r['sampling.time'])} (+${format(r['sampling.delay'])})`,
                        contradicts: 'a sample overlaps'}[r['sampling.verdict']];
      return [`${text}; ${sampling}.`, r['contact.status'] === 'no_contact_in_window' ? 'no_collision' : 'collision'];
    },
  });
  bindBodies(demo);
  for (const prefix of ['a', 'b'])
    demo.bind(sec.querySelector(`.motion-${prefix}`), ['vx', 'vy', 'vz', 'wx', 'wy', 'wz', 'g'].map((k) => prefix + '.' + k));
  demo.bind(sec.querySelector('.window'), ['t_max']);
  // The time slider spans the window; it is bound by hand (a fraction of t_max).
  const setTime = (t) => { demo.s.t = t; demo.update(); };
  time.addEventListener('input', () => setTime(time.valueAsNumber * demo.s.t_max));
  const sync = demo.sync.bind(demo);
  demo.sync = () => {
    sync();
    time.value = demo.s.t / demo.s.t_max;
    sec.querySelector('[data-testid=motion3d-time-value]').textContent = format(demo.s.t);
  };
  sec.querySelector('[data-testid=motion3d-to-contact]').addEventListener('click', () => {
    const t = demo.answer['contact.time'];
    if (Number.isFinite(t)) setTime(t);
  });
  const presets = sec.querySelector('.presets');
  for (const [name, state] of Object.entries(MOTION_PRESETS)) {
    const b = document.createElement('button');
    b.textContent = name;
    b.dataset.testid = 'motion3d-preset-' + name.replaceAll(' ', '-');
    b.addEventListener('click', () => { demo.s = {...state}; framed = false; demo.update(); });
    presets.append(b);
  }
  // The reduced frame (Eberly's figure 3.1): the first body the unit ball at the origin, the
  // second the axis-aligned ellipsoid moving along a straight line at the reduced velocity
  // (grey: its center's path over the window; arrow: the velocity); its point P nearest the
  // origin joined to it (red where |P| <= 1: they touch or overlap).
  let framed = false;
  function drawReduced(r) {
    const linear = r.motion === 'linear';
    reduced.canvas.hidden = !linear;
    reducedNote.hidden = linear;
    framed = framed && linear;
    if (!linear) return;
    reduced.clear();
    const identity = [1, 0, 0, 0, 1, 0, 0, 0, 1], c = r['reduced.center'], u = r['reduced.velocity'], p = r['reduced.p'];
    const along = (s) => c.map((x, k) => x + (s - demo.s.t) * u[k]);
    reduced.ellipsoid({center: [0, 0, 0], axes: identity, radii: [1, 1, 1]}, BLUE, {opacity: 0.5});
    reduced.ellipsoid({center: c, axes: identity, radii: r['reduced.radii']}, ORANGE, {opacity: 0.5});
    reduced.segment(along(0), along(demo.s.t_max), GREY);
    reduced.arrow(c, u, GREY);
    const touching = Math.hypot(...p) <= 1 + 1e-9;  // at the contact time, 1 to rounding
    reduced.segment([0, 0, 0], p, touching ? RED : '#222');
    reduced.point(p, touching ? RED : '#222');
    if (!framed) {  // the camera on the ball and the body's path, once per linear motion
      const mid = along(demo.s.t_max / 2).map((x) => x / 2), reach = 2 + Math.hypot(...along(0)) + Math.hypot(...along(demo.s.t_max));
      reduced.controls.target.set(...mid);
      reduced.camera.position.set(mid[0] + 0.5 * reach, mid[1] - 0.9 * reach, mid[2] + 0.6 * reach);
      reduced.controls.update();
      framed = true;
    }
    reduced.render();
  }
  // The window [0, t_max] left to right: each sample a dot (red: overlapping, green: apart),
  // the certified contact time a red line, the first overlapping sample ringed, the slider's
  // time a grey line.
  function drawSamples(r) {
    const c = strip.getContext('2d'), w = strip.width, h = strip.height, x = (t) => 20 + (w - 40) * t / demo.s.t_max;
    c.clearRect(0, 0, w, h);
    c.strokeStyle = '#999';
    c.lineWidth = 1;
    c.beginPath();
    c.moveTo(x(0), h / 2);
    c.lineTo(x(demo.s.t_max), h / 2);
    c.stroke();
    const mark = (t, color, width) => {
      if (!Number.isFinite(t)) return;
      c.strokeStyle = color;
      c.lineWidth = width;
      c.beginPath();
      c.moveTo(x(t), 6);
      c.lineTo(x(t), h - 6);
      c.stroke();
    };
    mark(demo.s.t, GREY, 1);
    mark(r['contact.time'], RED, 3);
    const times = r['samples.times'], hits = r['samples.overlap'];
    times.forEach((t, k) => {
      c.beginPath();
      c.arc(x(t), h / 2, 6, 0, 2 * Math.PI);
      c.fillStyle = hits[k] ? RED : GREEN;
      c.fill();
      if (t === r['sampling.time']) { c.strokeStyle = '#222'; c.lineWidth = 2; c.beginPath(); c.arc(x(t), h / 2, 10, 0, 2 * Math.PI); c.stroke(); }
    });
    c.fillStyle = '#222';
    c.font = '12px system-ui, sans-serif';
    c.fillText('0', x(0) - 3, h - 2);
    c.fillText(format(demo.s.t_max), x(demo.s.t_max) - 8, h - 2);
  }
  return demo;
}


// ---- collide and slide through a 3D level ---------------------------------------------------

// The level, a triangle mesh (z up): a floor, a box, a ramp rising along +x to a ledge, and a
// wall. Vertices [x, y, z]; triangles as vertex indices, each face's corners counterclockwise
// seen from outside.
const LEVEL = (() => {
  const vertices = [], triangles = [];
  const quad = (a, b, c, d) => {
    const k = vertices.length;
    vertices.push(a, b, c, d);
    triangles.push([k, k + 1, k + 2], [k, k + 2, k + 3]);
  };
  const box = ([x0, y0, z0], [x1, y1, z1]) => {  // its five faces but the bottom
    quad([x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]);
    quad([x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]);
    quad([x1, y1, z0], [x0, y1, z0], [x0, y1, z1], [x1, y1, z1]);
    quad([x0, y1, z0], [x0, y0, z0], [x0, y0, z1], [x0, y1, z1]);
    quad([x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]);
  };
  quad([-7, -7, 0], [7, -7, 0], [7, 7, 0], [-7, 7, 0]);     // floor
  box([0, 1, 0], [2.5, 3.5, 1.5]);                            // box
  quad([-4, -5, 0], [-1, -5, 1.5], [-1, -2, 1.5], [-4, -2, 0]);  // ramp
  box([-1, -5, 0], [1, -2, 1.5]);                             // the ledge it leads to
  quad([5, -7, 0], [5, 7, 0], [5, 7, 3], [5, -7, 3]);         // wall (facing -x)
  return {vertices, triangles};
})();

// An ellipsoid sent to a target through the level: the path round by round, the triangles hit
// (outlined red, a ring at each contact point) and touched at the end (filled red).
function slideDemo() {
  const level = {vertices: LEVEL.vertices.length, triangles: LEVEL.triangles.length};
  LEVEL.vertices.forEach(([x, y, z], k) => Object.assign(level, {[`v${k}.x`]: x, [`v${k}.y`]: y, [`v${k}.z`]: z}));
  LEVEL.triangles.forEach(([a, b, c], k) => Object.assign(level, {[`t${k}.a`]: a, [`t${k}.b`]: b, [`t${k}.c`]: c}));
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(LEVEL.triangles.flat().flatMap((k) => LEVEL.vertices[k]), 3));
  geometry.computeVertexNormals();
  const demo = new Demo3D('mesh_slide3d', {
    s: {...body('e', [-5, 0, 0.5], [0, 0, 0], [0.8, 0.5, 0.5]), tx: 3, ty: 2, tz: 0.5},
    hidden: ['path', 'hits.points', 'touched.points', ...bodyKeys('e')],
    params() { return {...this.s, ...level}; },
    handles: () => [demo.centerHandle('e'),
                    {name: 'target', at: () => [demo.s.tx, demo.s.ty, demo.s.tz],
                     set: ([x, y, z]) => Object.assign(demo.s, {tx: x, ty: y, tz: z})}],
    draw(v, a) {
      const hit = new Set(a.hits.split(',').filter(Boolean).map(Number)), touched = new Set(a.touched.split(',').filter(Boolean).map(Number));
      v.add(new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({color: '#bbb', roughness: 0.9, side: THREE.DoubleSide,
                                                                   polygonOffset: true, polygonOffsetFactor: 1})));
      LEVEL.triangles.forEach((t, k) => {
        if (!hit.has(k) && !touched.has(k)) return;
        const g = new THREE.BufferGeometry().setFromPoints(t.map((i) => new THREE.Vector3(...LEVEL.vertices[i])));
        const m = v.add(new THREE.Mesh(g, new THREE.MeshBasicMaterial({color: RED, side: THREE.DoubleSide, transparent: true,
                                                                    opacity: touched.has(k) ? 0.6 : 0.25})));
        m.userData.ownsGeometry = true;
      });
      const start = bodyOf(a, 'e');
      v.ellipsoid(start, GREY, {opacity: 0.3});
      v.ellipsoid({...start, center: [this.s.tx, this.s.ty, this.s.tz]}, '#ccc', {wire: true});
      for (let i = 3; i < a.path.length; i += 3) v.segment(Array.from(a.path.slice(i - 3, i)), Array.from(a.path.slice(i, i + 3)), ORANGE);
      for (let i = 0; i < a['hits.points'].length; i += 3) v.point(Array.from(a['hits.points'].slice(i, i + 3)), RED, 0.1);
      v.ellipsoid({...start, center: a.end}, a.status === 'moved' ? GREEN : RED);
    },
    headline(a) {
      if (a.status === 'overlapping_at_start') return [`The ellipsoid starts inside triangle ${a['relation.triangle']}: not moved.`, 'failed'];
      if (a.status === 'moved') return ['Moved the whole way in 1 round: nothing in between.', 'no_collision'];
      return [`${a.status === 'slid' ? 'Slid' : 'Blocked'} in ${a.rounds} round(s), ${a.contacts} ending at a contact` +
              `${a.hits ? ` (triangles ${a.hits})` : ''}; moved ${format(a.moved, 3)}.`, 'collision'];
    },
  });
  const sec = demo.section;
  demo.bind(sec.querySelector('.body-e'), SHAPE.map((k) => 'e.' + k));
  demo.bind(sec.querySelector('.body-e'), TURN.map((k) => 'e.' + k), {degrees: true});
  demo.bind(sec.querySelector('.target'), ['tx', 'ty', 'tz']);
  return demo;
}

// ---- live packing ---------------------------------------------------------------------------

const packingSphere = new THREE.SphereGeometry(1, 20, 10);  // many bodies: coarser

// A packing growing to jamming (answers.hpp's LivePacking), animated: the library runs it in
// a worker (packing_worker.js), one slice a frame of at most `per slice` collisions and about 15 ms,
// so the page's frames never wait for it; each frame draws the latest bodies. The density
// and the reduced pressure of each interval are plotted; at jamming, the contact network.
class PackingDemo extends Demo3D {
  constructor() {
    super('packing', {
      s: {dim: 2, n: 300, aspect: 1.6, rate: 0.1, pressure: 1000, seed: 1},
      hidden: ['centers', 'axes', 'radii', 'contacts.segments', 'history', 'box'],
      handles: () => [],
    });
    const sec = this.section;
    this.flat = sec.querySelector('canvas.flat');
    this.plot = sec.querySelector('canvas.plot');
    this.bind(sec.querySelector('.packing-params'), ['dim', 'n', 'aspect', 'rate', 'pressure', 'seed'], {step: 1});
    this.sliceMs = 0;     // the library work of the last slice (ms, wall clock)
    this.maxSliceMs = 0;  // the most of any slice since the start
    this.slices = [];     // that of every slice since the start
    this.pending = 0;     // messages to the worker not answered yet
    this.answer = {};
    this.latest = null;   // the latest message, drawn at the next frame
    this.worker = new Worker('packing_worker.js');
    this.worker.onmessage = ({data}) => {
      if (data.reply) this.pending--;
      this.sliceMs = data.ms;
      if (!data.reply) {
        this.slices.push(data.ms);
        this.maxSliceMs = Math.max(this.maxSliceMs, data.ms);
      }
      this.latest = data;
      if (data.reply && this.replied) this.replied();
    };
    const perSlice = sec.querySelector('[data-testid=packing-per-slice]');
    perSlice.addEventListener('input', () => this.worker.postMessage({perSlice: perSlice.valueAsNumber}));
    this.worker.postMessage({perSlice: perSlice.valueAsNumber});
    this.running = false;
    const button = (id, f) => sec.querySelector(`[data-testid=packing-${id}]`).addEventListener('click', f);
    const run = (running, message = {run: running}) => {
      this.running = running;
      this.send(message);
    };
    button('start', () => { this.start(); run(true); });
    button('pause', () => run(!this.running));
    button('step', () => run(false, {step: true}));  // the worker stops running for a step
    const loop = () => {
      if (this.latest) this.show(this.latest.state, this.latest.bodies);
      this.latest = null;
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }
  send(message) {
    this.pending++;
    this.worker.postMessage(message);
  }
  // A new run from the fields (the library's error, naming the field, where they are wrong);
  // `user`: pressed, so the location becomes its permalink. Resolves when the worker has it.
  start(user = true) {
    if (user) history.replaceState(null, '', this.permalink());
    this.slices = [];
    this.maxSliceMs = 0;
    this.send({start: this.params()});
    return new Promise((resolve) => {
      this.replied = () => {
        this.replied = null;
        const {state} = this.latest;
        if (state.error === undefined) this.frameView(state.box);
        resolve();
      };
    });
  }
  // The view of a new run in its box: the 2D canvas, or the 3D view with the camera on it.
  frameView(box) {
    const [w] = box, c = w / 2, v = this.view;
    v.controls.target.set(c, c, c);
    v.camera.position.set(c + 1.3 * w, c - 2.1 * w, c + 1.3 * w);
    v.controls.update();
    this.flat.hidden = box.length !== 2;
    v.canvas.hidden = box.length !== 3;
  }
  show(state, bodies) {
    const t0 = performance.now();
    this.answer = {...state, ...bodies};
    if (state.error === undefined) {
      if (state.box.length === 2) this.draw2(this.answer); else this.draw3(this.answer);
      this.drawPlot(this.answer);
    }
    renderAnswer(this, this.answer, 3);
    this.sync();
    this.section.querySelector('[data-testid=packing-library-ms]').textContent =
      `${this.sliceMs.toFixed(1)} ms (most ${this.maxSliceMs.toFixed(1)} ms)`;
    this.section.querySelector('.permalink').href = this.permalink();
    showTimes(this.sliceMs, performance.now() - t0);
  }
  update() { this.sync(); }  // fields change the next start, not the run
  headline(a) {
    if (a.status === 'jammed')
      return [`Jammed at density ${format(a.density)} (reduced pressure ${format(a.pressure)}) after ${a.collisions} collisions; ` +
              `${a.contacts} contacts, ${format(a.mean_contacts)} per body; ${a.overlapping} pairs overlapping.`, 'no_collision'];
    if (a.status === 'compressing') return [`Growing: density ${format(a.density)} after ${a.collisions} collisions.`, 'undecided'];
    return [`Stopped (${a.status}) at density ${format(a.density)} after ${a.collisions} collisions.`, 'undecided'];
  }
  draw2(a) {
    const c = this.flat.getContext('2d'), [w] = a.box, k = this.flat.width / w, y = (v) => this.flat.height - v * k;
    c.clearRect(0, 0, this.flat.width, this.flat.height);
    c.save();
    c.beginPath();
    c.rect(0, 0, this.flat.width, this.flat.height);
    c.clip();
    c.lineWidth = 1;
    for (let i = 0; i < a.radii.length / 2; i++) {
      const [x0, y0] = [a.centers[2 * i], a.centers[2 * i + 1]], angle = Math.atan2(a.axes[4 * i + 1], a.axes[4 * i]);
      for (const dx of [-w, 0, w]) for (const dy of [-w, 0, w]) {  // the periodic images across the edges
        c.beginPath();
        c.ellipse((x0 + dx) * k, y(y0 + dy), a.radii[2 * i] * k, a.radii[2 * i + 1] * k, -angle, 0, 2 * Math.PI);
        c.fillStyle = 'rgba(0, 85, 204, 0.35)';
        c.fill();
        c.strokeStyle = BLUE;
        c.stroke();
      }
    }
    const seg = a['contacts.segments'] || [];
    c.strokeStyle = RED;
    c.lineWidth = 1.5;
    for (let i = 0; i < seg.length; i += 4) {
      c.beginPath();
      c.moveTo(seg[i] * k, y(seg[i + 1]));
      c.lineTo(seg[i + 2] * k, y(seg[i + 3]));
      c.stroke();
    }
    c.restore();
  }
  draw3(a) {
    const v = this.view, n = a.radii.length / 3, [w] = a.box;
    v.clear();
    const mesh = v.add(new THREE.InstancedMesh(packingSphere, new THREE.MeshStandardMaterial({color: BLUE, roughness: 0.6}), n));
    const m = new THREE.Matrix4();
    for (let i = 0; i < n; i++) {
      const [ax, r, c] = [a.axes.subarray(9 * i), a.radii.subarray(3 * i), a.centers.subarray(3 * i)];
      m.set(ax[0] * r[0], ax[3] * r[1], ax[6] * r[2], c[0], ax[1] * r[0], ax[4] * r[1], ax[7] * r[2], c[1],
            ax[2] * r[0], ax[5] * r[1], ax[8] * r[2], c[2], 0, 0, 0, 1);
      mesh.setMatrixAt(i, m);
    }
    const box = v.add(new THREE.LineSegments(new THREE.EdgesGeometry(new THREE.BoxGeometry(w, w, w)),
                                             new THREE.LineBasicMaterial({color: '#555'})));
    box.position.set(w / 2, w / 2, w / 2);
    box.userData.ownsGeometry = true;
    const seg = a['contacts.segments'] || [];
    for (let i = 0; i < seg.length; i += 6) v.segment(Array.from(seg.subarray(i, i + 3)), Array.from(seg.subarray(i + 3, i + 6)), RED);
    v.render();
  }
  // Density (left scale, 0 to 1) and log10 of the reduced pressure (right scale, 0 to
  // log10 of the target) of each interval, against the interval.
  drawPlot(a) {
    const c = this.plot.getContext('2d'), w = this.plot.width, h = this.plot.height, hist = a.history;
    c.clearRect(0, 0, w, h);
    const count = hist.length / 2, x = (i) => 40 + (w - 80) * i / Math.max(1, count - 1);
    const series = (value, top, color) => {
      c.strokeStyle = color;
      c.lineWidth = 2;
      c.beginPath();
      for (let i = 0; i < count; i++) c[i ? 'lineTo' : 'moveTo'](x(i), h - 15 - (h - 30) * value(i) / top);
      c.stroke();
    };
    const top = Math.log10(this.s.pressure);
    series((i) => hist[2 * i], 1, BLUE);
    series((i) => Math.log10(hist[2 * i + 1]), top, ORANGE);
    c.fillStyle = '#222';
    c.font = '12px system-ui, sans-serif';
    c.fillText('density', 2, 12);
    c.fillText('1', 25, 18);
    c.fillText('0', 25, h - 12);
    c.fillStyle = ORANGE;
    c.fillText('log₁₀ p', w - 48, 12);
    c.fillText(format(top), w - 30, 24);
    c.fillStyle = '#555';
    c.fillText(`${count} intervals of 20 collisions per body`, w / 2 - 100, h - 1);
  }
}

// ---- start ------------------------------------------------------------------------------

const demos = {};

// The 2D page's contract for tests and tools (demo.js): the demos, their handles' client
// coordinates, and the mean time of n queries (or full frames, the WebGL drawing finished) of
// one demo.
window.ellipsectDemo = {
  demos,
  handleClient(id, name) {
    const h = demos[id].handles().find((x) => x.name === name);
    return demos[id].view.client(h.at());
  },
  client: (id, p) => demos[id].view.client(p),
  // The most any update of a demo on the page's thread waited for the library (ms).
  maxQueryMs: (id) => demos[id].maxQueryMs ?? 0,
  time(id, n, frame = false) {
    const d = demos[id], t0 = performance.now();
    for (let i = 0; i < n; i++) if (frame) d.update({user: false}); else d.query();
    if (frame) d.view.renderer.getContext().finish();  // the drawing done, not only queued
    return (performance.now() - t0) / n;
  },
};

createEllipsect().then(async (m) => {
  Module = m;
  for (const make of [pairDemo, motionDemo, slideDemo, () => new PackingDemo()]) {
    const d = make();
    demos[d.id] = d;
    const linked = d.restore(decodeURIComponent(location.hash));
    if (linked && d.lookAt) d.lookAt(d.s.dim);
    d.update({user: false});
    if (linked) d.section.scrollIntoView();
  }
  await demos.packing.start(false);
  ready();
});
