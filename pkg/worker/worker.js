// The module worker behind `lanepf/worker` (TrackerWorker): it owns one wasm instance and one
// Tracker, and answers the client's requests in order.
// Protocol: { id, op, args } -> { id, ok: true, result } | { id, ok: false, error, name,
// frame? }. Frames arrive as { data, width, height } with their buffers transferred; `track`
// hands the frame's buffer back, transferred, with its result. No top-level await: bundlers
// that emit workers as classic scripts (Vite's default) cannot run it.
import init, { Tracker } from '../web/lanepf.js';

let tracker = null;
let ready = null;

function need() {
  if (!tracker) {
    throw Object.assign(new Error('the tracker is not open (closed, or its construction failed)'),
      { name: 'LanepfStateError' });
  }
  return tracker;
}

/** What the estimate's extras ask for, read off the tracker after the step. */
function extras(t, want) {
  const out = {};
  if (want?.hypotheses > 0) out.hypotheses = t.hypotheses(want.hypotheses);
  if (want?.particles) out.particles = t.particles();
  if (want?.layers) out.layers = t.layers();
  return out;
}

const ops = {
  async open({ wasm, id, config }) {
    ready ??= init(wasm ? { module_or_path: wasm } : undefined);
    await ready;
    tracker?.free();
    tracker = null;
    tracker = new Tracker(id, config);
    return {
      result: {
        id: tracker.id, isStereo: tracker.isStereo, particleStride: tracker.particleStride,
        stepNames: tracker.stepNames(),
      },
    };
  },
  step({ frame, options }) {
    return { result: need().step(frame, options) };
  },
  track({ frame, options, want }) {
    const t = need();
    const t0 = performance.now();
    const estimate = t.step(frame, options);
    const ms = performance.now() - t0;
    const result = { estimate, ms, ...extras(t, want) };
    if (want?.frame) result.frame = frame;
    const transfer = [];
    if (result.frame) transfer.push(frame.data.buffer);
    if (result.particles) transfer.push(result.particles.buffer);
    return { result, transfer };
  },
  beginFrame({ frame, options }) {
    need().beginFrame(frame, options);
    return { result: null };
  },
  advance() {
    return { result: need().advance() };
  },
  nextStep() {
    return { result: need().nextStep ?? null };
  },
  reset() {
    need().reset();
    return { result: null };
  },
  particles() {
    const p = need().particles();
    return { result: p, transfer: [p.buffer] };
  },
  hypotheses({ max }) {
    return { result: need().hypotheses(max) };
  },
  layers() {
    return { result: need().layers() };
  },
  close() {
    tracker?.free();
    tracker = null;
    return { result: null };
  },
};

self.onmessage = async (e) => {
  const { id, op, args } = e.data ?? {};
  try {
    const handler = Object.hasOwn(ops, op) ? ops[op] : null;
    if (!handler) throw new Error(`lanepf worker: unknown request '${op}'`);
    const out = await handler(args ?? {});
    self.postMessage({ id, ok: true, result: out.result }, out.transfer ?? []);
  } catch (err) {
    // The error's kind (`name`, e.g. LanepfInputError) travels with its message, and a frame
    // that came with the request goes back with it.
    const frame = args?.frame;
    const back = frame?.data?.buffer?.byteLength ? frame : undefined;
    self.postMessage({ id, ok: false, error: err?.message ?? String(err), name: err?.name, frame: back },
      back ? [back.data.buffer] : []);
  }
};
