// The live packing's library work, off the page's thread (demo3d.js, PackingDemo): the
// library's one LivePacking (web/src/binding.cpp), run in slices of at most `perSlice`
// collisions that start no new chunk after SLICE_MS, one slice a frame (PERIOD_MS apart,
// start to start: at perSlice 1, 60 collisions a second, which a person can follow), each
// slice posting the state and the bodies. Messages in: {start: params}, {run: bool}, {perSlice: n}, {step: true}; each but
// perSlice answered with {reply: true, state, bodies}; slices post {state, bodies, ms}.
'use strict';
importScripts('ellipsect.js');

const SLICE_MS = 15, PERIOD_MS = 1000 / 60;
const CHUNK = 4;
let Module = null, running = false, perSlice = 400;
let started = {error: 'start', message: 'not started'};  // the last start's answer: a run, or why not
const live = () => started.error === undefined;
const loaded = createEllipsect().then((m) => { Module = m; });

function post(state, reply, ms = 0) {
  postMessage({reply, state, bodies: state.error === undefined ? Module.packingBodies() : {}, ms});
}

function slice() {
  if (!running) return;
  const t0 = performance.now();
  for (let done = 0; done < perSlice && performance.now() - t0 < SLICE_MS; done += CHUNK)
    Module.packingAdvance(Math.min(CHUNK, perSlice - done));
  const state = Module.packingState();
  running = state.status === 'compressing';
  const ms = performance.now() - t0;
  post(state, false, ms);
  if (running) setTimeout(slice, Math.max(0, PERIOD_MS - ms));
}

onmessage = async ({data}) => {
  await loaded;
  if (data.perSlice !== undefined) perSlice = data.perSlice;
  if (data.start !== undefined) {
    running = false;
    started = Module.packingStart(data.start);
    post(started, true);
  }
  if (data.step) {
    running = false;
    if (live()) Module.packingAdvance(1);
    post(live() ? Module.packingState() : started, true);
  }
  if (data.run !== undefined) {
    const start = data.run && !running && live();
    running = data.run && live();
    post(live() ? Module.packingState() : started, true);
    if (start) setTimeout(slice, 0);
  }
};
