// The demos: handles, drawing and read-outs. Every answer comes from the library through
// Module.answer(demo, params) (web/src/answers.hpp); this file only draws and converts.
import {BLUE, GREEN, GREY, ORANGE, RED, flatten, format, ready, renderAnswer, showTimes} from './common.js';

const SCALE = 40;     // pixels per world unit
const SNAP = 1 / 16;  // handles snap to this grid (exact binary fractions)
const GRAB = 12;      // pixels within which a handle is grabbed

let Module = null;

// ---- geometry of the view ----------------------------------------------------------

class View {
  constructor(canvas, scale = SCALE) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.scale = scale;
    this.ox = canvas.width / 2;
    this.oy = canvas.height / 2;
  }
  px([x, y]) { return [this.ox + x * this.scale, this.oy - y * this.scale]; }
  world(px, py) {
    const snap = (v) => Math.round(v / SNAP) * SNAP;
    return [snap((px - this.ox) / this.scale), snap((this.oy - py) / this.scale)];
  }
  clear() {
    const c = this.ctx;
    c.clearRect(0, 0, this.canvas.width, this.canvas.height);
    c.strokeStyle = '#eee';
    c.lineWidth = 1;
    for (let x = this.ox % this.scale; x < this.canvas.width; x += this.scale) this.line([x, 0], [x, this.canvas.height]);
    for (let y = this.oy % this.scale; y < this.canvas.height; y += this.scale) this.line([0, y], [this.canvas.width, y]);
  }
  line(a, b) {
    const c = this.ctx;
    c.beginPath();
    c.moveTo(a[0], a[1]);
    c.lineTo(b[0], b[1]);
    c.stroke();
  }
  segment(a, b, color, width = 2) {
    this.ctx.strokeStyle = color;
    this.ctx.lineWidth = width;
    this.line(this.px(a), this.px(b));
  }
  ellipse(e, color, {width = 2, dash = [], fill = null} = {}) {
    const c = this.ctx, [x, y] = this.px([e.cx, e.cy]);
    c.beginPath();
    c.ellipse(x, y, e.r0 * this.scale, e.r1 * this.scale, -e.angle, 0, 2 * Math.PI);
    if (fill) { c.fillStyle = fill; c.fill(); }
    c.setLineDash(dash);
    c.strokeStyle = color;
    c.lineWidth = width;
    c.stroke();
    c.setLineDash([]);
  }
  circle(ci, color, opts) { this.ellipse({cx: ci.cx, cy: ci.cy, angle: 0, r0: ci.r, r1: ci.r}, color, opts); }
  dot(p, color, {radius = 5, ring = false} = {}) {
    if (!p.every(Number.isFinite)) return;
    const c = this.ctx, [x, y] = this.px(p);
    c.beginPath();
    c.arc(x, y, radius, 0, 2 * Math.PI);
    if (ring) { c.strokeStyle = color; c.lineWidth = 2; c.stroke(); } else { c.fillStyle = color; c.fill(); }
  }
  polygon(flat, color, width = 1, fill = null) {  // flat: x0, y0, x1, y1, ... (closed)
    const c = this.ctx;
    c.beginPath();
    for (let i = 0; i < flat.length; i += 2) {
      const [x, y] = this.px([flat[i], flat[i + 1]]);
      if (i === 0) c.moveTo(x, y); else c.lineTo(x, y);
    }
    c.closePath();
    if (fill) { c.fillStyle = fill; c.fill(); }
    c.strokeStyle = color;
    c.lineWidth = width;
    c.lineJoin = 'round';
    c.stroke();
  }
  arrow(from, to, color) {
    this.segment(from, to, color, 2);
    const [x0, y0] = this.px(from), [x1, y1] = this.px(to), a = Math.atan2(y1 - y0, x1 - x0);
    const c = this.ctx;
    c.beginPath();
    c.moveTo(x1, y1);
    c.lineTo(x1 - 10 * Math.cos(a - 0.4), y1 - 10 * Math.sin(a - 0.4));
    c.lineTo(x1 - 10 * Math.cos(a + 0.4), y1 - 10 * Math.sin(a + 0.4));
    c.closePath();
    c.fillStyle = color;
    c.fill();
  }
  label(text, color = '#222', [x, y] = [10, 20], size = 15) {
    this.ctx.fillStyle = color;
    this.ctx.font = `bold ${size}px system-ui, sans-serif`;
    this.ctx.fillText(text, x, y);
  }
}

// ---- handles ------------------------------------------------------------------------

const add = (p, q) => [p[0] + q[0], p[1] + q[1]];
const sub = (p, q) => [p[0] - q[0], p[1] - q[1]];
const dir = (angle, r) => [r * Math.cos(angle), r * Math.sin(angle)];
const MIN_RADIUS = SNAP;

// A handle: name, where it is (world), what dragging it to a point does.
function handle(name, at, set) { return {name, at, set}; }

// An ellipse {cx, cy, angle, r0, r1}: center, the end of the first axis (length and angle,
// or only the length when `lockedAngle` gives the angle), the end of the second axis (length).
function ellipseHandles(prefix, e, lockedAngle = null) {
  const center = () => [e.cx, e.cy], angle = () => (lockedAngle ? lockedAngle() : e.angle);
  return [
    handle(prefix + '.center', center, ([x, y]) => { e.cx = x; e.cy = y; }),
    handle(prefix + '.axis0', () => add(center(), dir(angle(), e.r0)), (p) => {
      const d = sub(p, center());
      if (!lockedAngle) e.angle = Math.atan2(d[1], d[0]);
      e.r0 = Math.max(MIN_RADIUS, lockedAngle ? Math.abs(d[0] * Math.cos(angle()) + d[1] * Math.sin(angle())) : Math.hypot(d[0], d[1]));
    }),
    handle(prefix + '.axis1', () => add(center(), dir(angle() + Math.PI / 2, e.r1)), (p) => {
      const d = sub(p, center());
      e.r1 = Math.max(MIN_RADIUS, Math.hypot(d[0], d[1]));
    }),
  ];
}

function circleHandles(prefix, c) {
  return [
    handle(prefix + '.center', () => [c.cx, c.cy], ([x, y]) => { c.cx = x; c.cy = y; }),
    handle(prefix + '.radius', () => [c.cx + c.r, c.cy], ([x, y]) => { c.r = Math.hypot(x - c.cx, y - c.cy); }),
  ];
}

// ---- the demos ----------------------------------------------------------------------

// A demo: its state, params() for the library, handles(), draw(view, answer) and
// headline(answer) -> [text, class]. Keys listed in `hidden` are drawn, not tabulated.
// Optional: click(point) for a press away from every handle, remove(handle) for a
// shift-press on one.
class Demo {
  constructor(id, spec) {
    Object.assign(this, spec);
    this.id = id;
    this.section = document.getElementById(id);
    this.view = new View(this.section.querySelector('canvas'));
    this.table = this.section.querySelector('.readout');
    this.drag = null;
    const canvas = this.view.canvas;
    canvas.addEventListener('pointerdown', (ev) => {
      const [mx, my] = this.mouse(ev);
      let best = null, bestD = GRAB;
      for (const h of this.handles()) {
        const [x, y] = this.view.px(h.at());
        const d = Math.hypot(x - mx, y - my);
        if (d <= bestD) { best = h; bestD = d; }
      }
      if (best && ev.shiftKey && this.remove) { this.remove(best); this.update(); return; }
      if (best) { this.drag = best; canvas.setPointerCapture(ev.pointerId); return; }
      if (this.click) { this.click(this.view.world(mx, my)); this.update(); }
    });
    canvas.addEventListener('pointermove', (ev) => {
      if (!this.drag) return;
      this.drag.set(this.view.world(...this.mouse(ev)));
      this.update();
    });
    const end = () => { this.drag = null; };
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
  }
  mouse(ev) {
    const r = this.view.canvas.getBoundingClientRect();
    return [(ev.clientX - r.left) * this.view.canvas.width / r.width, (ev.clientY - r.top) * this.view.canvas.height / r.height];
  }
  // Client coordinates of a world point (for tests and tools that drive the page).
  client(p) {
    const r = this.view.canvas.getBoundingClientRect(), [x, y] = this.view.px(p);
    return [r.left + x * r.width / this.view.canvas.width, r.top + y * r.height / this.view.canvas.height];
  }
  query() { return Module.answer(this.id, this.params()); }
  update() {
    const t0 = performance.now();
    const answer = this.query();
    const t1 = performance.now();
    this.answer = answer;
    this.view.clear();
    if (answer.error === undefined) this.draw(this.view, answer);
    renderAnswer(this, answer);
    showTimes(t1 - t0, performance.now() - t0);
  }
  drawHandles() {
    for (const h of this.handles()) this.view.dot(h.at(), '#333', {radius: 6, ring: true});
  }
}

const pt = (a, i = 0) => [a[i], a[i + 1]];

function ellipseCircleDemo() {
  const e = {cx: -1, cy: 0, angle: 0.3, r0: 3, r1: 1.5}, c = {cx: 3.5, cy: 2, r: 1};
  return new Demo('ellipse_circle', {
    params: () => ({...flatten('e', e), ...flatten('c', c)}),
    handles: () => [...ellipseHandles('e', e), ...circleHandles('c', c)],
    draw(v, a) {
      const early = a['closed.verdict'] === 'early_out';
      v.ellipse(e, early ? RED : '#222');
      v.circle(c, early ? RED : BLUE);
      v.segment([c.cx, c.cy], pt(a['quartic.point']), GREY, 1);
      v.dot(pt(a['quartic.point']), GREEN, {radius: 8, ring: true});
      v.dot(pt(a['closed.point']), a['closed.verdict'] === 'collision' ? RED : '#222');
      if (a['closed.verdict'] === 'failed') v.label('closed form: NaN', RED);
      this.drawHandles();
    },
    headline(a) {
      const v = a['closed.verdict'];
      if (v === 'failed') return ['The published closed form failed (NaN). Robust quartic: ' + a['quartic.verdict'] + '.', 'failed'];
      if (v === 'early_out') return ['Collision (early out: the circle\'s center is inside the ellipse).', 'collision'];
      return [(v === 'collision' ? 'Collision' : 'No collision') + ' by the closed form; robust quartic: ' + a['quartic.verdict'] + '.', v];
    },
  });
}

function segmentCircleDemo() {
  const s = {ax: -4, ay: -2, bx: 3, by: 1.5}, c = {cx: 1, cy: -2, r: 1.25};
  return new Demo('segment_circle', {
    params: () => ({...flatten('s', s), ...flatten('c', c)}),
    handles: () => [
      handle('s.a', () => [s.ax, s.ay], ([x, y]) => { s.ax = x; s.ay = y; }),
      handle('s.b', () => [s.bx, s.by], ([x, y]) => { s.bx = x; s.by = y; }),
      ...circleHandles('c', c)],
    draw(v, a) {
      const color = a.verdict === 'collision' ? RED : '#222';
      v.segment([s.ax, s.ay], [s.bx, s.by], color, 3);
      v.circle(c, color);
      v.label('a', '#555', v.px([s.ax, s.ay]).map((q) => q - 12));
      v.label('b', '#555', v.px([s.bx, s.by]).map((q) => q - 12));
      this.drawHandles();
    },
    headline: (a) => [(a.verdict === 'collision' ? 'Collision' : 'No collision') + '; the center is ' +
                      (a.side === 'on_line' ? 'on the line' : 'on the ' + a.side + ' of a → b') + '.', a.verdict],
  });
}

function polygonalDemo() {
  const a = {cx: -1, cy: 0, angle: 0.4, r0: 4, r1: 1.5};
  const b = {cx: 3, cy: 2.5, angle: -0.6, r0: 1.5, r1: 0.75};
  const c = {cx: 3, cy: 2.5, r: 1};
  const sec = document.getElementById('polygonal');
  const body = sec.querySelector('[data-testid=polygonal-body]');
  const level = sec.querySelector('[data-testid=polygonal-level]');
  const cover = sec.querySelector('[data-testid=polygonal-cover]');
  // With parallel axes the second ellipse takes the first one's angle (its own is kept).
  const shownB = () => (body.value === 'parallel' ? {...b, angle: a.angle} : b);
  const demo = new Demo('polygonal', {
    hidden: ['inscribed.', 'circumscribed.'],
    params() {
      const second = body.value === 'circle' ? flatten('c', c) : flatten('b', shownB());
      return {...flatten('a', a), ...second, body: body.value === 'circle' ? 0 : 1, level: Number(level.value),
              cover: body.value === 'circle' && cover.checked ? 1 : 0};
    },
    handles: () => [...ellipseHandles('a', a),
                    ...(body.value === 'circle' ? circleHandles('c', c)
                                                : ellipseHandles('b', b, body.value === 'parallel' ? () => a.angle : null))],
    draw(v, r) {
      const n = r.drawn_levels;
      for (let k = 0; k < n; k++) {
        const shade = Math.round(200 - 170 * (k + 1) / n);
        const color = `rgb(${shade},${shade},${shade})`;
        v.polygon(r['inscribed.' + k], color);
        v.polygon(r['circumscribed.' + k], color);
      }
      const color = {collision: RED, no_collision: GREEN, undecided: ORANGE}[r.verdict] || '#222';
      v.ellipse(a, color, {width: 1});
      if (body.value === 'circle') v.circle(c, color); else v.ellipse(shownB(), color);
      this.drawHandles();
    },
    headline(r) {
      const text = {collision: 'Collision', no_collision: 'No collision', undecided: 'Undecided'}[r.verdict] || r.verdict;
      const band = r.verdict === 'undecided' ? ` at level ${r.level}: the gap is in [${format(r.gap_lo)}, ${format(r.gap_hi)}], ` +
        `error bound ${format(r.error_bound)}` : ` at level ${r.level} after ${r.iterations} bisection(s)`;
      return [text + band + ` (exact: ${r.exact.replace('_', ' ')}).`, r.verdict];
    },
  });
  const changed = () => {
    cover.disabled = body.value !== 'circle';
    sec.querySelector('[data-testid=polygonal-level-value]').textContent = level.value;
    demo.update();
  };
  for (const el of [body, level, cover]) el.addEventListener('input', changed);
  cover.disabled = body.value !== 'circle';
  return demo;
}

function sweptDemo() {
  const a = {cx: -4, cy: -1, angle: 0.5, r0: 2, r1: 1, vx: 2, vy: 0.5};
  const b = {cx: 4, cy: 1.5, angle: -0.4, r0: 1.5, r1: 0.75, vx: -1, vy: -0.5};
  const T_MAX = 4;
  const sec = document.getElementById('swept');
  const time = sec.querySelector('[data-testid=swept-time]');
  const inset = new View(sec.querySelector('.inset'));
  const velocityHandle = (name, e) => handle(name, () => [e.cx + e.vx, e.cy + e.vy], ([x, y]) => { e.vx = x - e.cx; e.vy = y - e.cy; });
  const shape = (e) => ({cx: e.cx, cy: e.cy, angle: e.angle, r0: e.r0, r1: e.r1});
  const at = (e, center) => ({...shape(e), cx: center[0], cy: center[1]});
  const demo = new Demo('swept', {
    params: () => ({...flatten('a', a), ...flatten('b', b), t_max: T_MAX, t: Number(time.value)}),
    handles: () => [...ellipseHandles('a', a), velocityHandle('a.velocity', a),
                    ...ellipseHandles('b', b), velocityHandle('b.velocity', b)],
    draw(v, r) {
      v.ellipse(shape(a), GREY, {width: 1, dash: [5, 4]});
      v.ellipse(shape(b), GREY, {width: 1, dash: [5, 4]});
      const hit = r.status === 'hit' || r.status === 'touching_at_start';
      if (hit) {
        const moved = (e) => at(e, [e.cx + r.time * e.vx, e.cy + r.time * e.vy]);
        v.ellipse(moved(a), '#bbb', {width: 3});
        v.ellipse(moved(b), '#bbb', {width: 3});
        v.arrow(pt(r.point), add(pt(r.point), pt(r.normal)), RED);
        v.dot(pt(r.point), RED);
      }
      const overlapping = !['separated', 'touching'].includes(r.relation_t);
      v.ellipse(at(a, pt(r.a_center_t)), overlapping ? RED : BLUE);
      v.ellipse(at(b, pt(r.b_center_t)), overlapping ? RED : '#222');
      v.arrow([a.cx, a.cy], [a.cx + a.vx, a.cy + a.vy], BLUE);
      v.arrow([b.cx, b.cy], [b.cx + b.vx, b.cy + b.vy], '#222');
      this.drawHandles();
      drawInset(r);
    },
    headline(r) {
      const text = {hit: `First contact at t = ${format(r.time)}`, touching_at_start: 'Touching at t = 0',
                    overlapping_at_start: 'Overlapping at t = 0', no_contact_in_window: `No contact for t in [0, ${T_MAX}]`}[r.status] || r.status;
      return [text + '.', r.status === 'no_contact_in_window' ? 'no_collision' : 'collision'];
    },
  });
  // The reduced frame: unit circle at the origin, the axis-aligned ellipse (center K),
  // P, and the relative velocity at K; scaled to fit.
  function drawInset(r) {
    const k = pt(r['reduced.center']), e = pt(r['reduced.radii']);
    const extent = Math.max(1.2, Math.hypot(...k) + Math.max(...e)) * 1.1;
    inset.scale = inset.canvas.width / 2 / extent;
    const c = inset.ctx;
    c.clearRect(0, 0, inset.canvas.width, inset.canvas.height);
    c.strokeStyle = '#eee';
    inset.line([0, inset.oy], [inset.canvas.width, inset.oy]);
    inset.line([inset.ox, 0], [inset.ox, inset.canvas.height]);
    inset.circle({cx: 0, cy: 0, r: 1}, BLUE);
    inset.ellipse({cx: k[0], cy: k[1], angle: 0, r0: e[0], r1: e[1]}, '#222');
    inset.arrow(k, add(k, pt(r['reduced.velocity'])), GREY);
    inset.segment([0, 0], pt(r['reduced.p']), GREY, 1);
    inset.dot(pt(r['reduced.p']), RED, {radius: 4});
    inset.label('P', RED, add(inset.px(pt(r['reduced.p'])), [6, -6]));
  }
  time.max = T_MAX;
  const changed = () => {
    sec.querySelector('[data-testid=swept-time-value]').textContent = Number(time.value).toFixed(2);
    demo.update();
  };
  time.addEventListener('input', changed);
  sec.querySelector('[data-testid=swept-to-contact]').addEventListener('click', () => {
    const t = demo.answer && demo.answer.time;
    if (Number.isFinite(t)) { time.value = t; changed(); }
  });
  return demo;
}

function relationDemo() {
  const a = {cx: -1.5, cy: 0, angle: 0.3, r0: 3, r1: 1.25}, b = {cx: 2.5, cy: 1, angle: -0.8, r0: 2, r1: 1};
  return new Demo('relation', {
    params: () => ({...flatten('a', a), ...flatten('b', b)}),
    handles: () => [...ellipseHandles('a', a), ...ellipseHandles('b', b)],
    draw(v, r) {
      const c = v.ctx;
      if (r.area > 0) {  // the intersection, shaded: b filled inside a's clip
        c.save();
        c.beginPath();
        const [x, y] = v.px([a.cx, a.cy]);
        c.ellipse(x, y, a.r0 * v.scale, a.r1 * v.scale, -a.angle, 0, 2 * Math.PI);
        c.clip();
        v.ellipse(b, 'transparent', {fill: 'rgba(220,0,0,0.15)'});
        c.restore();
      }
      v.ellipse(a, BLUE);
      v.ellipse(b, '#222');
      if (Number.isFinite(r.distance) && r.point_a.every(Number.isFinite)) {
        v.segment(pt(r.point_a), pt(r.point_b), ORANGE, 2);
        v.arrow(pt(r.point_a), add(pt(r.point_a), pt(r.normal)), ORANGE);
        v.dot(pt(r.point_a), BLUE, {radius: 4});
        v.dot(pt(r.point_b), '#222', {radius: 4});
      }
      const kinds = r['crossings.kinds'].split(',');
      for (let i = 0; i < r['crossings.count']; i++)
        v.dot(pt(r['crossings.points'], 2 * i), RED, {radius: 5, ring: kinds[i] === 'tangent'});
      this.drawHandles();
    },
    headline(r) {
      const d = r.distance < 0 ? `penetration depth ${format(-r.distance)}` : `distance ${format(r.distance)}`;
      return [`${r.relation.replaceAll('_', ' ')}; ${d}; ${r['crossings.count']} crossing(s); IoU ${format(r.iou)}.`,
              r.relation === 'separated' ? 'no_collision' : 'collision'];
    },
  });
}

// A room of half-planes (outward normals into the room), the ellipse and the point it is
// sent to; the library moves it there, sliding along the walls it meets (slide.hpp).
function slideDemo() {
  const e = {cx: -2, cy: 1, angle: 0.4, r0: 1.5, r1: 0.75}, target = {x: 4, y: -4.5};
  const walls = [{px: 0, py: -3.5, nx: 0, ny: 1}, {px: -6.5, py: 0, nx: 1, ny: 0},
                 {px: 5, py: 0, nx: -1, ny: 0.5}, {px: 0, py: 4.5, nx: 0, ny: -1}];
  const params = () => {
    const out = {...flatten('e', e), tx: target.x, ty: target.y, walls: walls.length};
    walls.forEach((w, k) => Object.assign(out, flatten('w' + k, w)));
    return out;
  };
  return new Demo('slide', {
    params,
    handles: () => [...ellipseHandles('e', e), handle('target', () => [target.x, target.y], ([x, y]) => { target.x = x; target.y = y; })],
    draw(v, a) {
      const c = v.ctx, far = 100;
      for (const w of walls) {  // the solid side, shaded: the plane's line pushed far out
        const t = [-w.ny, w.nx], o = [w.px, w.py], back = [-w.nx * far, -w.ny * far];
        const corners = [add(o, dir(Math.atan2(t[1], t[0]), far)), add(o, dir(Math.atan2(-t[1], -t[0]), far))];
        c.beginPath();
        [corners[0], corners[1], add(corners[1], back), add(corners[0], back)].forEach((p, i) => {
          const [x, y] = v.px(p);
          if (i === 0) c.moveTo(x, y); else c.lineTo(x, y);
        });
        c.closePath();
        c.fillStyle = 'rgba(0,0,0,0.12)';
        c.fill();
      }
      const end = pt(a.end), stopped = a.status !== 'moved';
      v.ellipse(e, GREY, {dash: [5, 4]});
      v.ellipse({...e, cx: target.x, cy: target.y}, '#ccc', {dash: [2, 4]});
      v.segment([e.cx, e.cy], [target.x, target.y], '#ccc', 1);
      v.segment([e.cx, e.cy], end, ORANGE, 2);
      v.ellipse({...e, cx: end[0], cy: end[1]}, stopped ? RED : GREEN, {width: 3});
      this.drawHandles();
    },
    headline(a) {
      if (a.status === 'overlapping_at_start') return ['The ellipse starts inside a wall: not moved.', 'failed'];
      if (a.status === 'moved') return ['Moved the whole way: nothing in between.', 'no_collision'];
      return [`${a.status === 'slid' ? 'Slid' : 'Blocked'} after ${a.contacts} contact(s); moved ${format(a.moved)}.`,
              'collision'];
    },
  });
}

// A small level of triangles (segments where an index repeats): a floor with a ramp and a
// step, a slope, two blocks with a narrow gap between them, a triangular block, a post and a
// slanted ceiling. The library moves the ellipse through it towards the target, sliding
// along what it meets (slide.hpp, mesh.hpp).
function levelMesh() {
  const vertices = [], triangles = [];
  const piece = (points, tris) => {
    tris.forEach((t) => triangles.push(t.map((i) => vertices.length + i)));
    vertices.push(...points);
  };
  const quad = (...points) => piece(points, [[0, 1, 2], [0, 2, 3]]);
  quad([-7, -5], [-1, -5], [-1, -4], [-7, -4]);                // floor
  quad([-1, -5], [2, -5], [2, -3.25], [-1, -3.25]);            // a step up
  quad([2, -5], [7, -5], [7, -1.5], [2, -3.25]);               // slope
  piece([[-6, -4], [-3.5, -4], [-3.5, -3.25]], [[0, 1, 2]]);   // ramp
  quad([-5, 0.5], [-1.5, 0.5], [-1.5, 1.25], [-5, 1.25]);      // blocks with a gap
  quad([-0.25, 0.5], [3, 0.5], [3, 1.25], [-0.25, 1.25]);
  piece([[3.5, 1.75], [6, 1.75], [4.75, 3]], [[0, 1, 2]]);     // triangular block
  piece([[5.5, -0.5], [5.5, 1]], [[0, 1, 1]]);                 // post
  piece([[-6.5, 3], [-3, 4.25]], [[0, 1, 1]]);                 // ceiling
  return {vertices, triangles};
}

function meshSlideDemo() {
  const e = {cx: 4.5, cy: -1, angle: 0.3, r0: 1, r1: 0.5}, target = {x: 0, y: -4.5};
  const level = levelMesh();
  const corners = (k) => level.triangles[k].flatMap((i) => level.vertices[i]);
  const params = () => {
    const out = {...flatten('e', e), tx: target.x, ty: target.y,
                 vertices: level.vertices.length, triangles: level.triangles.length};
    level.vertices.forEach(([x, y], k) => Object.assign(out, {[`v${k}.x`]: x, [`v${k}.y`]: y}));
    level.triangles.forEach(([a, b, c], k) => Object.assign(out, {[`t${k}.a`]: a, [`t${k}.b`]: b, [`t${k}.c`]: c}));
    return out;
  };
  return new Demo('mesh_slide', {
    params,
    handles: () => [...ellipseHandles('e', e), handle('target', () => [target.x, target.y], ([x, y]) => { target.x = x; target.y = y; })],
    draw(v, a) {
      const indices = (list) => new Set(list ? list.split(',').map(Number) : []);
      const touched = indices(a.touched), hit = indices(a.hits), inside = !['separated', 'touching'].includes(a.relation);
      level.triangles.forEach((_, k) => {
        const red = touched.has(k) || (inside && k === a['relation.triangle']);
        v.polygon(corners(k), red || hit.has(k) ? RED : '#777', hit.has(k) ? 3 : 2, red ? 'rgba(220,0,0,0.3)' : 'rgba(0,0,0,0.15)');
      });
      level.triangles.forEach((t, k) => {  // the index, at the centroid
        const [x, y] = v.px([0, 1].map((j) => t.reduce((sum, i) => sum + level.vertices[i][j], 0) / 3));
        v.label(String(k), '#555', [x - 4, y + 4], 11);
      });
      const end = pt(a.end), stopped = a.status !== 'moved';
      v.ellipse(e, GREY, {dash: [5, 4]});
      v.ellipse({...e, cx: target.x, cy: target.y}, '#ccc', {dash: [2, 4]});
      v.segment([e.cx, e.cy], [target.x, target.y], '#ccc', 1);
      for (let i = 2; i < a.path.length; i += 2) {
        v.segment(pt(a.path, i - 2), pt(a.path, i), ORANGE, 2);
        v.dot(pt(a.path, i), ORANGE, {radius: 3});
      }
      v.ellipse({...e, cx: end[0], cy: end[1]}, stopped ? RED : GREEN, {width: 3});
      for (let i = 0; i < a['hits.points'].length; i += 2) v.dot(pt(a['hits.points'], i), RED, {ring: true});
      for (let i = 0; i < a['touched.points'].length; i += 2) v.dot(pt(a['touched.points'], i), RED);
      this.drawHandles();
    },
    headline(a) {
      if (a.status === 'overlapping_at_start') return [`The ellipse starts inside triangle ${a['relation.triangle']}: not moved.`, 'failed'];
      if (a.status === 'moved') return ['Moved the whole way in 1 round: nothing in between.', 'no_collision'];
      return [`${a.status === 'slid' ? 'Slid' : 'Blocked'} in ${a.rounds} round(s), ${a.contacts} ending at a contact` +
              `${a.hits ? ` (triangles ${a.hits})` : ''}; moved ${format(a.moved)}.`, 'collision'];
    },
  });
}

// Points to ellipses (geometry.hpp): click to add a point, drag one to move it, shift-click
// one to remove it. Blue: the minimum-area enclosing ellipse (its support points ringed);
// green: the largest ellipse inside the points' hull (grey); orange: the least-squares one.
function geometryDemo() {
  const start = [[-4, 1], [-3, 2.5], [-1, 3.25], [1.5, 3], [3.5, 1.5], [4, -0.5], [2.5, -2.25], [0, -2.75],
                 [-2.5, -2], [-3.75, -0.75]];
  let points = start.map((q) => [...q]);
  const shape = (a, name) => ({cx: a[name + '.center'][0], cy: a[name + '.center'][1], angle: a[name + '.angle'],
                               r0: a[name + '.radii'][0], r1: a[name + '.radii'][1]});
  const section = document.getElementById('geometry');
  section.querySelector('[data-testid=geometry-clear]').addEventListener('click', () => { points = []; demos.geometry.update(); });
  section.querySelector('[data-testid=geometry-reset]').addEventListener('click', () => {
    points = start.map((q) => [...q]);
    demos.geometry.update();
  });
  return new Demo('geometry', {
    hidden: ['hull.', 'enclose.support'],
    params: () => {
      const out = {n: points.length};
      points.forEach(([x, y], k) => { out[`p${k}.x`] = x; out[`p${k}.y`] = y; });
      return out;
    },
    handles: () => points.map((q, k) => handle('p' + k, () => q, ([x, y]) => { q[0] = x; q[1] = y; })),
    click(p) { points.push(p); },
    remove(h) { points.splice(Number(h.name.slice(1)), 1); },
    draw(v, a) {
      if (a['hull.faces'] > 0) {  // the hull: each edge's line cut by its neighbours'
        const at = a['hull.points'], n = a['hull.normals'], m = a['hull.faces'], corners = [];
        for (let k = 0; k < m; k++) {
          const j = (k + 1) % m;  // corner of lines k and j: n . x = n . p for both
          const bk = n[2 * k] * at[2 * k] + n[2 * k + 1] * at[2 * k + 1], bj = n[2 * j] * at[2 * j] + n[2 * j + 1] * at[2 * j + 1];
          const det = n[2 * k] * n[2 * j + 1] - n[2 * k + 1] * n[2 * j];
          corners.push((bk * n[2 * j + 1] - bj * n[2 * k + 1]) / det, (n[2 * k] * bj - n[2 * j] * bk) / det);
        }
        v.polygon(corners, GREY, 1, 'rgba(0,0,0,0.04)');
      }
      if (a['enclose.status'] !== undefined) v.ellipse(shape(a, 'enclose'), BLUE);
      if (a['inscribe.status'] !== undefined) v.ellipse(shape(a, 'inscribe'), GREEN);
      if (a['fit.status'] !== undefined) v.ellipse(shape(a, 'fit'), ORANGE, {dash: [6, 4]});
      const support = a['enclose.support'] || [];
      for (let i = 0; i < support.length; i += 2) v.dot(pt(support, i), BLUE, {radius: 9, ring: true});
      for (const q of points) v.dot(q, '#222', {radius: 4});
    },
    headline(a) {
      const said = (name, what) => (a[name + '.status'] !== undefined ? `${what} ${a[name + '.status'].replaceAll('_', ' ')}`
                                                                       : `no ${what} (${a[name + '.error'].replace(/^ellipsect: /, '')})`);
      const text = [said('enclose', 'enclosing'), said('inscribe', 'inscribed'), said('fit', 'fit')].join('; ') + '.';
      const all = ['enclose', 'inscribe', 'fit'].every((k) => a[k + '.status'] !== undefined);
      return [text, all ? 'no_collision' : 'undecided'];
    },
  });
}

// ---- start --------------------------------------------------------------------------

const demos = {};

// What tests and tools use to drive the page: the demos, their handles' client
// coordinates, and the mean time of n queries (or full frames) of one demo.
window.ellipsectDemo = {
  demos,
  handleClient(id, name) {
    const h = demos[id].handles().find((x) => x.name === name);
    return demos[id].client(h.at());
  },
  client: (id, p) => demos[id].client(p),
  time(id, n, frame = false) {
    const d = demos[id], t0 = performance.now();
    for (let i = 0; i < n; i++) if (frame) d.update(); else d.query();
    return (performance.now() - t0) / n;
  },
};

createEllipsect().then((m) => {
  Module = m;
  for (const make of [ellipseCircleDemo, segmentCircleDemo, polygonalDemo, sweptDemo, relationDemo, slideDemo,
                      meshSlideDemo, geometryDemo]) {
    const d = make();
    demos[d.id] = d;
    d.update();
  }
  ready();
});
