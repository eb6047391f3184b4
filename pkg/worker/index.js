// `lanepf/worker`: a Tracker in a module Web Worker, behind promises, so that a page's main
// thread never waits on the filter. Frames go to the worker as transferred buffers, not copies.
//
//   import { TrackerWorker } from 'lanepf/worker';
//   const tracker = await TrackerWorker.create('lee-cpf', { camera });
//   const lane = await tracker.step(video);          // ImageData, ImageBitmap, VideoFrame, <video>, ...
//   tracker.terminate();
//
// The worker is started with `new Worker(new URL('./worker.js', import.meta.url), { type:
// 'module' })`, the form Vite and webpack 5 recognise and bundle; `options.worker` takes a
// Worker made elsewhere instead.
import { readFrame } from '../frames/index.js';

/** An Error with lanepf's kind in `name`. */
function errorOf(message, name) {
  const e = new Error(message);
  if (name) e.name = name;
  return e;
}

/** A frame as the worker takes it: `{ data, width, height }` over a buffer of its own. */
function toMessage(source, size, copy) {
  const frame = readFrame(source, size);
  let { data } = frame;
  const whole = data.byteOffset === 0 && data.byteLength === data.buffer.byteLength;
  // A view into a larger buffer (or one the caller keeps) is copied, so that transferring it
  // moves nothing else.
  if (copy || !whole || typeof SharedArrayBuffer !== 'undefined' && data.buffer instanceof SharedArrayBuffer) {
    data = data.slice();
  }
  return { data, width: frame.width, height: frame.height };
}

/** A Tracker running in its own module worker; every method returns a promise. */
export class TrackerWorker {
  /**
   * Starts a worker, instantiates the wasm module in it and builds the tracker. Rejects with the
   * constructor's Error (e.g. a `LanepfConfigError` naming the option) and stops the worker.
   *
   * @param id a tracker id (`trackerIds()`)
   * @param config the tracker's config, as for `new Tracker(id, config)`
   * @param options `{ worker, wasm }`: a Worker to use instead of starting one (running this
   *   package's `worker/worker.js`, or a worker of your own that calls `serve()` from
   *   `worker/serve.js`); where the worker fetches `lanepf_bg.wasm` from (default: next to the
   *   package's `web/lanepf.js`)
   */
  static async create(id, config, options = {}) {
    const client = await TrackerWorker.connect(options);
    try {
      await client.open(id, config);
    } catch (e) {
      client.terminate();
      throw e;
    }
    return client;
  }

  /**
   * Starts the worker (or takes `options.worker`) and instantiates the wasm module in it, with
   * no tracker yet: `open(id, config)` builds one. For an app whose own worker serves other ops
   * first (a scene, a calibrator). Rejects when the worker or the wasm fails to start.
   */
  static async connect(options = {}) {
    const worker = options.worker
      ?? new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    const client = new TrackerWorker(worker);
    try {
      client.version = await client.request('version', { wasm: options.wasm && String(options.wasm) });
    } catch (e) {
      client.terminate();
      throw e;
    }
    return client;
  }

  /** Use `TrackerWorker.create`. */
  constructor(worker) {
    this.worker = worker;
    this.pending = new Map();
    this.nextId = 1;
    this.info = null;
    this.version = null;
    this.closed = false;
    worker.onmessage = (e) => {
      const { id, ok, result, error, name, frame } = e.data ?? {};
      const p = this.pending.get(id);
      if (!p) return;
      this.pending.delete(id);
      if (ok) p.resolve(result);
      else p.reject(Object.assign(errorOf(error, name), frame ? { frame } : {}));
    };
    const fail = (message) => {
      const err = errorOf(`lanepf worker failed: ${message}`);
      for (const p of this.pending.values()) p.reject(err);
      this.pending.clear();
    };
    worker.onerror = (e) => { e.preventDefault?.(); fail(e.message ?? 'an error in the worker'); };
    worker.onmessageerror = () => fail('a message could not be read');
  }

  /**
   * Sends one request `{ op, args }` (with `transfer`, the buffers to move); resolves with its
   * result. For ops a worker of your own adds with `serve({ op(args, ctx) { ... } })`.
   */
  request(op, args = {}, transfer = []) {
    if (this.closed) return Promise.reject(errorOf('the TrackerWorker was terminated', 'LanepfStateError'));
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      try {
        this.worker.postMessage({ id, op, args }, transfer);
      } catch (e) {
        this.pending.delete(id);
        reject(e);
      }
    });
  }

  /** The tracker's id. */
  get id() { return this.info?.id; }

  /** Whether the tracker needs the right camera's frame with every step (`danescu-stereo`). */
  get isStereo() { return this.info?.isStereo ?? false; }

  /** Numbers per particle in `particles()`. */
  get particleStride() { return this.info?.particleStride ?? 0; }

  /** The filter steps of one frame in per-step mode (`beginFrame` / `advance`). */
  get stepNames() { return this.info?.stepNames ?? []; }

  /**
   * Reads the frame (and `options.right`) off its source, sends the pixels to the worker
   * (transferred) and returns the message and the transfer list.
   */
  frameArgs(frame, options = {}) {
    const { right, motion, width, height, copy } = options;
    const size = width || height ? { width, height } : undefined;
    const left = toMessage(frame, size, copy);
    const stepOptions = {};
    const transfer = [left.data.buffer];
    if (right !== undefined) {
      stepOptions.right = toMessage(right, { width: left.width, height: left.height }, copy);
      transfer.push(stepOptions.right.data.buffer);
    }
    if (motion !== undefined) stepOptions.motion = motion;
    return { args: { frame: left, options: stepOptions }, transfer };
  }

  /**
   * Tracks one frame; resolves with the estimate. `frame` is anything `readFrame` takes
   * (ImageData, ImageBitmap, VideoFrame, <video>, canvas, <img>, `{ data, width, height }`);
   * options: `right` (the right camera's frame, for danescu-stereo), `motion` (EgoMotion),
   * `width` / `height` (read the frame at this size), `copy` (send a copy: otherwise an
   * ImageData's buffer is transferred and the ImageData is empty afterwards).
   */
  async step(frame, options) {
    const { args, transfer } = this.frameArgs(frame, options);
    return this.request('step', args, transfer);
  }

  /**
   * As `step`, with more back: `{ estimate, ms, hypotheses?, particles?, layers?,
   * resamplings?, frame? }`: `ms` the step's time in the worker, and what `want` asks for
   * (`hypotheses: n`, `particles: true`, `layers: true`, `resamplings: true`, `frame: true`
   * for the frame's pixels back, transferred).
   */
  async track(frame, options = {}) {
    const { args, transfer } = this.frameArgs(frame, options);
    return this.request('track', { ...args, want: options.want ?? {} }, transfer);
  }

  /** Starts a frame in per-step mode (same arguments as `step`). */
  async beginFrame(frame, options) {
    const { args, transfer } = this.frameArgs(frame, options);
    return this.request('beginFrame', args, transfer);
  }

  /**
   * Replaces the tracker in the same worker (same wasm instance): e.g. another id, or the same
   * one for a new camera. Rejects as `create` does; the worker then has no tracker until the
   * next successful `open`.
   */
  async open(id, config) {
    this.info = null;
    this.info = await this.request('open', { id, config });
    return this;
  }

  /** Frees the tracker, keeping the worker (calls other than `open` then reject). */
  async close() {
    this.info = null;
    await this.request('close');
  }

  /** Runs the next filter step: the estimate after the last, `null` before it. */
  advance() { return this.request('advance'); }

  /** Index into `stepNames` of the next step, or `null` when no frame is in progress. */
  nextStep() { return this.request('nextStep'); }

  /** Forgets the past. */
  reset() { return this.request('reset'); }

  /** The particle cloud after the last step (`particleStride` numbers per particle). */
  particles() { return this.request('particles'); }

  /** At most `max` particles drawn as lane hypotheses. */
  hypotheses(max) { return this.request('hypotheses', { max }); }

  /** Pictures of the tracker's cues after the last frame. */
  layers() { return this.request('layers'); }

  /** The resampling decisions of the last `step` / `advance`, as the filters made them. */
  resamplings() { return this.request('resamplings'); }

  /** Stops the worker (its wasm memory goes with it); pending calls reject. */
  terminate() {
    if (this.closed) return;
    this.closed = true;
    this.worker.terminate();
    const err = errorOf('the TrackerWorker was terminated', 'LanepfStateError');
    for (const p of this.pending.values()) p.reject(err);
    this.pending.clear();
  }
}

// `using tracker = await TrackerWorker.create(...)` terminates it at the end of the scope.
if (typeof Symbol.dispose === 'symbol') {
  TrackerWorker.prototype[Symbol.dispose] = function dispose() { this.terminate(); };
}
