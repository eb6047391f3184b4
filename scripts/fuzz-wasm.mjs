#!/usr/bin/env node
// Seeded fuzzing of the wasm package's JavaScript API (issue 19): random calls on every class
// and function (Camera, Scene, TestRoad, Tracker of every id, Calibrator, trackerDefaults, ...)
// with valid, mutated and hostile arguments (wrong types, numeric strings, fractions, 2^32 +
// n, NaN, BigInt, Symbols, cyclic, 10 000-deep and Proxy objects, throwing and re-entrant
// getters, fake and huge arrays), objects freed at random. Every call must return or throw an
// Error named LanepfConfigError / LanepfInputError / LanepfStateError (or, for a call on an
// object already freed, wasm-bindgen's own Error); a trap (WebAssembly.RuntimeError), any other
// exception, an object left locked, a call over 2 s, or wasm memory growing without bound
// fails the run.
//
//   node scripts/fuzz-wasm.mjs [--calls N] [--seed S] [--wide] [--trace-from I] [--json]
//
// (make fuzz-wasm.) A run depends on the seed alone: --trace-from I prints every call from the
// I-th on before making it, to replay a failure.
//
// A tracker's numeric options stay within a factor of 3 of their defaults (wrong types, NaN,
// null and unknown keys still come) unless --wide, which also draws finite extremes (5e-324,
// 1e-9, 1e9, 1e200, 1e300, negatives, 2^31): the range checks' territory (issue 19, part 3),
// where a slow or panicking step is a missing range check.
//
// The calls run in a worker thread; the main thread is a watchdog that ends the run when one
// call has not returned within 30 s (a hang), naming the call's index to replay with the seed.
import { Worker, isMainThread, parentPort, workerData } from 'node:worker_threads';
import { readFileSync, writeSync } from 'node:fs';

const HANG_MS = 2000;
const WATCHDOG_MS = 30000;
const KINDS = new Set(['LanepfConfigError', 'LanepfInputError', 'LanepfStateError']);
let showing = false; // the fuzzer itself is printing an argument: getters do nothing

if (isMainThread) {
  const args = process.argv.slice(2);
  const opt = (name, fallback) => {
    const i = args.indexOf(name);
    return i >= 0 ? Number(args[i + 1]) : fallback;
  };
  const calls = opt('--calls', 100000);
  const seed = opt('--seed', 1);
  const json = args.includes('--json');
  const progress = new Int32Array(new SharedArrayBuffer(8)); // [call index, busy]
  const wide = args.includes('--wide');
  const traceFrom = opt('--trace-from', Infinity);
  const worker = new Worker(new URL(import.meta.url), { workerData: { calls, seed, wide, traceFrom, progress } });
  let last = { index: -1, since: Date.now() };
  const watchdog = setInterval(() => {
    const index = Atomics.load(progress, 0);
    if (index !== last.index) last = { index, since: Date.now() };
    else if (Atomics.load(progress, 1) && Date.now() - last.since > WATCHDOG_MS) {
      clearInterval(watchdog);
      console.error(`fuzz-wasm: call ${index} (seed ${seed}) has not returned in ${WATCHDOG_MS / 1000} s: a hang`);
      process.exit(1);
    }
  }, 500);
  worker.on('message', (report) => {
    clearInterval(watchdog);
    if (json) console.log(JSON.stringify(report));
    else printReport(report);
    const failed = report.crashes + report.hangs + report.unclassified + report.locked > 0 || !report.memoryBounded;
    process.exitCode = failed ? 1 : 0;
  });
  worker.on('error', (err) => {
    clearInterval(watchdog);
    console.error('fuzz-wasm: the worker failed:', err);
    process.exitCode = 1;
  });
} else {
  parentPort.postMessage(await fuzz(workerData));
}

function printReport(r) {
  const mb = (b) => `${(b / 2 ** 20).toFixed(1)} MiB`;
  console.log(`fuzz-wasm: seed ${r.seed}${r.wide ? ' (--wide)' : ''}, ${r.cases} calls in ${(r.seconds).toFixed(1)} s`);
  console.log(`  returned          ${r.returned}`);
  console.log(`  clean errors      ${r.cleanErrors} (config ${r.byKind.LanepfConfigError}, input ${r.byKind.LanepfInputError}, state ${r.byKind.LanepfStateError})`);
  console.log(`  freed-object errors ${r.freedErrors} (wasm-bindgen's own, for calls on freed objects)`);
  console.log(`  crashes (traps)   ${r.crashes}`);
  console.log(`  other exceptions  ${r.unclassified}`);
  console.log(`  locked objects    ${r.locked}`);
  console.log(`  hangs (> ${HANG_MS / 1000} s)     ${r.hangs}; slowest call ${r.slowestMs.toFixed(0)} ms (${r.slowest})`);
  console.log(`  wasm memory       start ${mb(r.memory.start)}, half-way ${mb(r.memory.half)}, end ${mb(r.memory.end)} (bounded: ${r.memoryBounded})`);
  for (const f of r.failures) console.log(`  FAILURE at call ${f.index}: ${f.call}: ${f.error}`);
}

async function fuzz({ calls, seed, wide, traceFrom, progress }) {
  const pkg = await import('../pkg/web/lanepf.js');
  const wasm = pkg.initSync({ module: readFileSync(new URL('../pkg/web/lanepf_bg.wasm', import.meta.url)) });
  // The simulator is its own module (lanepf/sim), with its own memory.
  const sim = await import('../pkg/sim/lanepf_sim.js');
  const simWasm = sim.initSync({ module: readFileSync(new URL('../pkg/sim/lanepf_sim_bg.wasm', import.meta.url)) });
  const memoryBytes = () => wasm.memory.buffer.byteLength + simWasm.memory.buffer.byteLength;
  const { Calibrator, Camera, Tracker } = pkg;
  const { Scene, TestRoad } = sim;
  const rng = mulberry32(seed);
  const R = makeRandom(rng);

  // Valid material: small cameras (so that a step is milliseconds) and their frames.
  const SIZES = [[64, 48], [96, 72], [128, 96]];
  const ids = pkg.trackerIds();
  const names = sim.scenarios().map((s) => s.name);
  const defaults = Object.fromEntries(ids.map((id) => [id, pkg.trackerDefaults(id)]));
  const material = SIZES.map(([w, h]) => {
    const scene = new Scene('highway-curve', { width: w, height: h, seed: 3 });
    const m = { w, h, camera: scene.camera(), left: [], right: [] };
    for (let f = 0; f < 4; f++) { m.left.push(scene.render(f * 10)); m.right.push(scene.renderRight(f * 10)); }
    scene.free();
    return m;
  });
  const HUGE = new Uint8Array(2 ** 31); // not touched: only its length is ever read

  const live = []; // { kind, serial, obj, m (material), freed }
  let nextSerial = 0;
  const stats = {
    seed, wide, cases: 0, returned: 0, cleanErrors: 0, freedErrors: 0, crashes: 0, unclassified: 0,
    locked: 0, hangs: 0, slowestMs: 0, slowest: '',
    byKind: { LanepfConfigError: 0, LanepfInputError: 0, LanepfStateError: 0 },
    memory: { start: memoryBytes(), half: 0, end: 0 }, memoryBounded: true, failures: [],
  };

  // --- argument generators --------------------------------------------------------------
  let acting = false; // a call of the package is under way
  let nested = 0; // calls made by a getter during one
  // Hostile objects are remembered, so that the generators never spread or walk one
  // themselves (their traps would throw in the fuzzer, not in the package).
  const hostile = new WeakSet();
  const hostileValue = () => {
    const v = hostileChoice();
    if ((typeof v === 'object' && v !== null) || typeof v === 'function') hostile.add(v);
    return v;
  };
  const hostileChoice = () => R.pick([
    () => NaN, () => Infinity, () => -Infinity, () => -1, () => 0, () => 0.5, () => 2 ** 32 + 7,
    () => 2 ** 53 + 2, () => 1e300, () => -1e300, () => 5e-324, () => '12', () => '', () => 'x'.repeat(R.int(0, 200)),
    () => null, () => undefined, () => true, () => [], () => [1, 'a'], () => ({}), () => 10n,
    () => Symbol('s'), () => () => 3, () => new Float64Array(3), () => new Date(0),
    () => cyclic(), () => deep(R.pick([10, 200, 10000])), () => throwingGetter(), () => proxy(),
    () => reentrant(), () => new Map([[1, 2]]), () => Object.create(null),
    () => ({ toJSON() {} }), () => { const v = R.pick([5, 'x', null, [1]]); return { toJSON: () => v }; },
  ])();
  const cyclic = () => { const o = { a: 1 }; o.self = o; return o; };
  const deep = (n) => { let o = {}; for (let i = 0; i < n; i++) o = { a: o }; return o; };
  const throwingGetter = () => Object.defineProperty({}, 'x', { enumerable: true, get() { throw new Error('getter'); } });
  const proxy = () => R.pick([
    () => new Proxy({}, { ownKeys() { throw new Error('ownKeys'); } }),
    () => new Proxy({ a: 1 }, { get() { throw new Error('get'); } }),
    () => { const p = Proxy.revocable({}, {}); p.revoke(); return p.proxy; },
    () => new Proxy(new Uint8Array(16), {}),
  ])();
  // A getter that calls into a live object (maybe the one being called): must not lock it.
  const reentrant = () => {
    const o = { a: 1 };
    Object.defineProperty(o, 'b', {
      enumerable: true,
      get() {
        // Only while the package reads it (not when the fuzzer prints it), and not nested, so
        // that the run depends on the seed alone.
        if (!acting || nested > 0 || showing) return 2;
        nested++;
        try {
          const target = live.length ? R.pick(live) : null;
          if (target && !target.freed) {
            if (R.chance(0.2)) { target.freed = true; target.obj.free(); } else callMethod(target);
          }
        } finally {
          nested--;
        }
        return 2;
      },
    });
    return o;
  };

  /** A number near `x` (same sign, within a factor 3), kept whole when `x` is. */
  const near = (x) => {
    if (wide && R.chance(0.3)) return R.pick([5e-324, 1e-9, 1e9, 1e200, -x, x * 1e6, 2 ** 31]);
    const y = x * 3 ** R.float(-1, 1);
    return Number.isInteger(x) ? Math.max(Math.round(y), x > 0 ? 1 : 0) : y;
  };
  /** Mutates a valid value: mostly nearby values, sometimes a hostile one. */
  const mutate = (v) => {
    if (R.chance(0.3)) {
      const h = hostileValue();
      // A finite number of the wrong size for a tracker option is the range checks' test
      // (--wide), not this one's.
      return trackerOptions && typeof h === 'number' && Number.isFinite(h) ? near(typeof v === 'number' ? v : 1) : h;
    }
    if (typeof v === 'number') return near(v);
    if (typeof v === 'boolean') return !v;
    if (hostile.has(v)) return v;
    // A frame's pixels: cut short, never spread (a 1280x720 frame has 3.7 million indices). A
    // DataView (one of the hostile values) has no subarray: it is cut by a new view.
    if (v instanceof DataView) return R.chance(0.5) ? v : new DataView(v.buffer, v.byteOffset, R.int(0, v.byteLength));
    if (ArrayBuffer.isView(v)) return R.chance(0.5) ? v : v.subarray(0, R.int(0, v.length));
    if (Array.isArray(v)) return v.map((x) => (R.chance(0.5) ? mutate(x) : x));
    if (v && typeof v === 'object') return mutateObject(v);
    return v;
  };
  const mutateObject = (o, depth = 0) => {
    const out = { ...o };
    const keys = Object.keys(out);
    const n = R.int(0, 2);
    for (let i = 0; i < n; i++) {
      const r = rng();
      if (r < 0.1) out[R.pick(['bogus', 'camera', 'particles', 'widht', '__proto__x'])] = hostileValue();
      else if (r < 0.2 && keys.length) delete out[R.pick(keys)];
      else if (keys.length) {
        const k = R.pick(keys);
        const plain = out[k] && typeof out[k] === 'object' && !hostile.has(out[k]) && !Array.isArray(out[k])
          && !ArrayBuffer.isView(out[k]);
        out[k] = plain && depth < 2
          ? mutateObject(out[k], depth + 1) : mutate(out[k]);
      }
    }
    return out;
  };

  const cameraArg = (m) => (R.chance(0.85) ? m.camera : R.chance(0.5) ? mutateObject(m.camera) : hostileValue());
  let trackerOptions = false; // drawing a tracker's options (numbers stay near the defaults)
  const trackerConfig = (id, m) => {
    const base = { ...defaults[id], camera: m.camera, seed: R.int(0, 1000), particles: R.int(20, 300) };
    if (id.startsWith('liu')) base.init_particles = R.int(0, 50);
    if (id === 'lee-cpf') base.stage2_particles = R.int(0, 200);
    if (R.chance(0.5)) delete base.particles;
    trackerOptions = !wide;
    try {
      return R.chance(0.7) ? base : R.chance(0.8) ? mutateObject(base) : hostileValue();
    } finally {
      trackerOptions = false;
    }
  };
  const frameArg = (m, right = false) => R.chance(0.85)
    ? R.pick(right ? m.right : m.left)
    : R.pick([
      () => ({ length: -5 }), () => ({ length: 1e10 }), () => HUGE, () => new Uint8Array(R.int(0, 64)),
      () => new Float32Array(m.w * m.h * 4), () => Array.from({ length: 12 }, () => 0), () => 'pixels',
      () => new Uint8Array(m.w * m.h * 4).buffer, () => new DataView(new ArrayBuffer(8)),
      () => Object.setPrototypeOf({ length: m.w * m.h * 4 }, Uint8Array.prototype),
      () => new Proxy(R.pick(m.left), {}), () => R.pick(m.left).subarray(4), hostileValue,
    ])();
  const sizeArg = (x) => (R.chance(0.9) ? x
    : R.chance(0.2) ? hostileValue() : R.pick([x + 0.5, String(x), -x, 2 ** 32 + x, x * 2, 0, NaN]));
  const indexArg = () => (R.chance(0.85) ? R.int(0, 500) : R.pick([-1, 1.5, '3', 2 ** 32, 2 ** 32 + 3, NaN, null, 10n, {}]));
  const motionArg = () => {
    const m = { t_s: R.float(0, 100), speed_mps: R.float(-40, 40), yaw_rate: R.float(-0.5, 0.5) };
    return R.chance(0.7) ? m : R.chance(0.7) ? mutateObject(m) : hostileValue();
  };
  // The frame-object form of step (issue 21): `{ data, width, height }` and `{ right, motion }`.
  const frameObjectArg = (m, right = false) => {
    const f = { data: frameArg(m, right), width: sizeArg(m.w), height: sizeArg(m.h) };
    return R.chance(0.85) ? f : R.chance(0.5) ? mutateObject(f) : hostileValue();
  };
  const stepOptionsArg = (m) => {
    const o = {};
    if (R.chance(0.5)) o.right = frameObjectArg(m, true);
    if (R.chance(0.5)) o.motion = motionArg();
    return R.chance(0.85) ? o : R.chance(0.5) ? mutateObject(o) : hostileValue();
  };

  // --- calls -----------------------------------------------------------------------------
  const construct = () => {
    const m = R.pick(material);
    const what = R.pick(['tracker', 'tracker', 'tracker', 'scene', 'road', 'camera', 'calibrator']);
    const serial = nextSerial++;
    let obj;
    if (what === 'tracker') {
      const id = R.chance(0.9) ? R.pick(ids) : R.pick(['nope', 5, {}, null, 'x'.repeat(100), Symbol('id')]);
      const config = trackerConfig(typeof id === 'string' && ids.includes(id) ? id : 'lee-cpf', m);
      setCall(() => `#${serial} = new Tracker(${show(id)}, ${show(config)})`);
      obj = new Tracker(id, config);
    } else if (what === 'scene') {
      const name = R.chance(0.9) ? R.pick(names) : hostileValue();
      const options = R.chance(0.8) ? R.pick([{ width: m.w, height: m.h, seed: R.int(0, 99) }, { camera: m.camera }, undefined])
        : mutateObject({ width: m.w, height: m.h, seed: 1 });
      setCall(() => `#${serial} = new Scene(${show(name)}, ${show(options)})`);
      obj = new Scene(name, options);
    } else if (what === 'road') {
      const camera = cameraArg(m);
      const options = R.chance(0.5) ? undefined : mutateObject({ lane_width_m: 3.6, speed_mps: 20, fps: 30 });
      setCall(() => `#${serial} = new TestRoad(${show(camera)}, ${show(options)})`);
      obj = new TestRoad(camera, options);
    } else if (what === 'camera') {
      const camera = cameraArg(m);
      setCall(() => `#${serial} = new Camera(${show(camera)})`);
      obj = new Camera(camera);
    } else {
      const options = R.chance(0.7) ? { width: m.w, height: m.h, stable_frames: R.int(1, 6) }
        : R.chance(0.7) ? mutateObject({ width: m.w, height: m.h, intrinsics: m.camera, hfov_deg: 60 }) : hostileValue();
      setCall(() => `#${serial} = new Calibrator(${show(options)})`);
      obj = new Calibrator(options);
    }
    live.push({ kind: what, serial, obj, m, freed: false });
    while (live.length > 12) {
      const old = live.shift();
      if (!old.freed) { old.freed = true; old.obj.free(); }
    }
  };

  const callMethod = (entry) => {
    const { kind, obj, m } = entry;
    const w = sizeArg(m.w), h = sizeArg(m.h);
    const call = (name, ...args) => {
      setCall(() => `${kind} #${entry.serial}.${name}(${args.map(show).join(', ')})`);
      return obj[name](...args);
    };
    switch (kind) {
      case 'tracker': return R.pick([
        () => { if (obj.isStereo && R.chance(0.8)) obj.setRight(R.pick(m.right), m.w, m.h); return call('step', frameArg(m), w, h); },
        () => call('setRight', frameArg(m, true), w, h),
        () => call('step', frameObjectArg(m), stepOptionsArg(m)),
        () => call('beginFrame', frameObjectArg(m), stepOptionsArg(m)),
        () => call('beginFrame', frameArg(m), w, h),
        () => call('advance'),
        () => call('setEgoMotion', motionArg()),
        () => call('hypotheses', R.chance(0.8) ? R.int(0, 50) : indexArg()),
        () => call('particles'), () => call('layers'), () => call('reset'), () => call('stepNames'),
        () => obj.particleStride + obj.nextStep + obj.id + obj.isStereo,
      ])();
      case 'scene': return R.pick([
        () => call('render', indexArg()), () => call('renderRight', indexArg()), () => call('truth', indexArg()),
        () => call('camera'), () => obj.width + obj.height + obj.frames,
      ])();
      case 'road': return R.pick([() => call('render', indexArg()), () => call('truth', indexArg())])();
      case 'camera': return R.pick([
        () => call('projectRoad', R.chance(0.8) ? R.float(-5, 80) : hostileValue(), R.chance(0.8) ? R.float(-10, 10) : hostileValue()),
        () => call('roadPoint', R.chance(0.8) ? R.float(0, m.w) : hostileValue(), R.chance(0.8) ? R.float(0, m.h) : hostileValue()),
        // (Typed arrays only: the binding's glue, not lanepf, handles other values for `xy`.)
        () => call('projectRoadPoints', Float64Array.from({ length: R.int(0, 9) },
          () => (R.chance(0.8) ? R.float(-20, 80) : R.pick([NaN, Infinity, -Infinity, 1e308, -0])))),
        () => call('toJSON'),
      ])();
      default: return R.pick([
        () => call('feed', frameArg(m), w, h), () => call('estimate'), () => call('observation'),
        () => call('markingPixels'), () => call('options'), () => call('reset'),
      ])();
    }
  };

  const functionCall = () => R.pick([
    () => { const id = R.chance(0.7) ? R.pick(ids) : hostileValue(); setCall(() => `trackerDefaults(${show(id)})`); return pkg.trackerDefaults(id); },
    () => pkg.trackerIds(), () => sim.scenarios(), () => pkg.version(), () => sim.version(),
  ])();

  let describeCall = () => '';
  let index = 0;
  /** Names the call about to be made (printed first from --trace-from on). */
  const setCall = (describe) => {
    describeCall = describe;
    // Written at once (a worker's console is flushed only when its loop is idle).
    if (index >= traceFrom) writeSync(2, `call ${index}: ${describe()}\n`);
  };
  const half = Math.floor(calls / 2);
  const t0 = performance.now();
  for (let i = 0; i < calls; i++) {
    Atomics.store(progress, 0, i);
    Atomics.store(progress, 1, 1);
    describeCall = () => '(no description)';
    index = i;
    const start = performance.now();
    acting = true;
    try {
      const r = rng();
      if (r < 0.12 || live.length === 0) construct();
      else if (r < 0.15) functionCall();
      else if (r < 0.18) {
        // Free a live object; one in ten stays listed, so that calls on freed objects are tried.
        const k = Math.floor(rng() * live.length);
        const e = live[k];
        setCall(() => `${e.kind}.free()`);
        if (R.chance(0.9)) live.splice(k, 1);
        const wasFreed = e.freed;
        e.freed = true;
        if (!wasFreed || R.chance(0.1)) e.obj.free();
      }
      else callMethod(R.pick(live));
      stats.returned++;
    } catch (err) {
      classify(err, i);
    }
    acting = false;
    Atomics.store(progress, 1, 0);
    const ms = performance.now() - start;
    if (ms > stats.slowestMs) { stats.slowestMs = ms; stats.slowest = describeCall().slice(0, 160); }
    if (ms > HANG_MS) { stats.hangs++; fail(i, `took ${ms.toFixed(0)} ms`); }
    stats.cases++;
    if (i === half) stats.memory.half = memoryBytes();
  }
  for (const e of live) if (!e.freed) e.obj.free();
  stats.memory.end = memoryBytes();
  // Bounded: at most 1 GiB, and the second half of the run grew memory by at most 64 MiB (a
  // leak of a frame or a tracker per call would grow it steadily).
  stats.memoryBounded = stats.memory.end <= 2 ** 30 && stats.memory.end - stats.memory.half <= 64 * 2 ** 20;
  stats.seconds = (performance.now() - t0) / 1000;
  return stats;

  function classify(err, i) {
    if (err instanceof WebAssembly.RuntimeError) { stats.crashes++; fail(i, `trap: ${err.message}`); return; }
    if (err instanceof Error && KINDS.has(err.name)) { stats.cleanErrors++; stats.byKind[err.name]++; return; }
    const message = String(err?.message ?? err);
    if (/null pointer passed to rust|attempted to take ownership/.test(message)) { stats.freedErrors++; return; }
    if (/recursive use of an object/.test(message)) { stats.locked++; fail(i, message); return; }
    stats.unclassified++;
    fail(i, `${err?.name}: ${message}`);
  }
  function fail(index, error) {
    if (stats.failures.length < 20) stats.failures.push({ index, call: describeCall().slice(0, 300), error: error.slice(0, 300) });
  }
}

/** Short text of an argument, for failure reports (its getters do nothing meanwhile). */
function show(v) {
  showing = true;
  try {
    return showText(v);
  } finally {
    showing = false;
  }
}

function showText(v) {
  if (typeof v === 'bigint') return `${v}n`;
  if (typeof v === 'symbol' || typeof v === 'function') return String(v);
  if (ArrayBuffer.isView(v)) return `${v.constructor.name}(${v.length ?? v.byteLength})`;
  try {
    return JSON.stringify(v, (k, x) => (typeof x === 'bigint' ? `${x}n` : x))?.slice(0, 120) ?? String(v);
  } catch {
    return '(unprintable object)';
  }
}

/** A seeded 32-bit generator (mulberry32): numbers in [0, 1). */
function mulberry32(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

function makeRandom(rng) {
  return {
    pick: (list) => list[Math.floor(rng() * list.length)],
    int: (lo, hi) => lo + Math.floor(rng() * (hi - lo + 1)),
    float: (lo, hi) => lo + rng() * (hi - lo),
    chance: (p) => rng() < p,
  };
}
