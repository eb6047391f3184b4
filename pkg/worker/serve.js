// The request loop of `lanepf/worker`'s module worker: one wasm instance, one Tracker, the
// client's requests answered in order. `worker.js` runs it as it is; a worker of your own can
// run it with ops of its own next to the tracker's (a scene to render, a calibrator to feed):
//
//   import { serve } from 'lanepf/worker/serve.js';
//   serve({ render({ index }, ctx) { ... return { result, transfer }; } });
//
// and the page calls them with `TrackerWorker.request('render', { index })`.
// Protocol: { id, op, args } -> { id, ok: true, result } | { id, ok: false, error, name,
// frame? }. Frames arrive as { data, width, height } with their buffers transferred; `track`
// hands the frame's buffer back, transferred, with its result. No top-level await: bundlers
// that emit workers as classic scripts (Vite's default) cannot run it.
import init, * as lanepf from '../web/lanepf.js';

const { Tracker } = lanepf;
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
  if (want?.resamplings) out.resamplings = t.resamplings();
  return out;
}

const ops = {
  version() {
    return { result: lanepf.version() };
  },
  open({ id, config }) {
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
    // Each layer's values are a Float32Array of their own: transferred, not copied.
    for (const layer of result.layers ?? []) transfer.push(layer.values.buffer);
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
    const layers = need().layers();
    return { result: layers, transfer: layers.map((l) => l.values.buffer) };
  },
  resamplings() {
    return { result: need().resamplings() };
  },
  close() {
    tracker?.free();
    tracker = null;
    return { result: null };
  },
};

/**
 * Answers the client's requests in this worker: the tracker's ops and `extra`, an object of
 * `op(args, ctx)` functions (sync or async) returning `{ result, transfer? }`; `ctx` is
 * `{ lanepf, tracker }`: the initialised package module and the open Tracker (or null).
 */
export function serve(extra = {}) {
  for (const name of Object.keys(extra)) {
    if (Object.hasOwn(ops, name)) throw new Error(`lanepf worker: op '${name}' is the tracker's own`);
  }
  const ctx = { lanepf, get tracker() { return tracker; } };
  self.onmessage = async (e) => {
    const { id, op, args } = e.data ?? {};
    try {
      // The first request starts the wasm (from args.wasm when it says where).
      ready ??= init(args?.wasm ? { module_or_path: args.wasm } : undefined);
      await ready;
      const own = Object.hasOwn(ops, op) ? ops[op] : null;
      const handler = own ?? (Object.hasOwn(extra, op) ? extra[op] : null);
      if (!handler) throw new Error(`lanepf worker: unknown request '${op}'`);
      const out = await handler(args ?? {}, ctx);
      self.postMessage({ id, ok: true, result: out?.result ?? null }, out?.transfer ?? []);
    } catch (err) {
      // The error's kind (`name`, e.g. LanepfInputError) travels with its message, and a frame
      // that came with the request goes back with it.
      const frame = args?.frame;
      const back = frame?.data?.buffer?.byteLength ? frame : undefined;
      self.postMessage({ id, ok: false, error: err?.message ?? String(err), name: err?.name, frame: back },
        back ? [back.data.buffer] : []);
    }
  };
}
