// The npm package as users get it: `npm pack` of pkg/ (after `make pkg`), installed from the
// tarball into small apps, each run in headless Chromium:
//   web/index.html   plain ES modules with an import map (no bundler)
//   web/worker.html  the package inside a module Web Worker
//   web/client.html  `lanepf/worker` (TrackerWorker, on its own worker and on one of the app's
//                    that serves ops of its own) and `lanepf/frames` (readFrame, FrameReader)
//   vite/            a Vite app: index.html uses `lanepf` with init(), on the main thread and in
//                    a worker it bundles; bundler.html uses `lanepf/bundler` (no init()) and
//                    `lanepf/worker`; built (`vite build`, with and without vite-plugin-wasm)
//                    and served, and under the dev server (`vite`)
//   webpack/         the bundler.html app built by webpack 5 with no configuration but its entry
// and its TypeScript types: a correct program must pass `tsc --strict`, and a program with
// deliberate type errors must fail on exactly the lines that have them. Vite, vite-plugin-wasm,
// webpack and TypeScript are the repository's devDependencies (`npm ci`, scripts/setup.sh); the
// apps live under target/ so that they resolve them from the repository's node_modules, and the
// tarball is installed with `npm install --offline` (it has no dependencies).
import test from 'node:test';
import assert from 'node:assert/strict';
import { execFile, spawn } from 'node:child_process';
import { createServer } from 'node:net';
import { cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, renameSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import webpack from 'webpack';
import { start, open } from '../e2e/browser.mjs';
import { serve } from '../../scripts/serve.mjs';

const here = fileURLToPath(new URL('.', import.meta.url));
const repo = join(here, '..', '..');
const pkg = join(repo, 'pkg');
const fixtures = join(here, 'fixtures');
const bin = (name) => join(repo, 'node_modules', '.bin', name);

/** Runs a command; rejects with its output when it fails or takes longer than `timeout` ms. */
function run(cmd, args, cwd, timeout = 120_000) {
  return new Promise((resolve, reject) => {
    execFile(cmd, args, { cwd, timeout, maxBuffer: 16 << 20, env: { ...process.env, NO_COLOR: '1', FORCE_COLOR: '0' } },
      (err, stdout, stderr) => {
        if (err) {
          reject(new Error(`\`${cmd} ${args.join(' ')}\` in ${cwd} failed (${err.code ?? err.signal}):\n`
            + `${stdout}\n${stderr}`));
        } else {
          resolve({ stdout, stderr });
        }
      });
  });
}

// --- set-up: pack, copy the fixtures, install the tarball ------------------------------------

assert.ok(existsSync(join(pkg, 'web', 'lanepf_bg.wasm')),
  'pkg/web/lanepf_bg.wasm is missing: run `make pkg` first');
for (const tool of ['vite', 'tsc']) {
  assert.ok(existsSync(bin(tool)), `node_modules/.bin/${tool} is missing: run \`npm ci\` (or scripts/setup.sh)`);
}
mkdirSync(join(repo, 'target'), { recursive: true });
const tmp = mkdtempSync(join(repo, 'target', 'npm-test-'));
const removeTmp = () => rmSync(tmp, { recursive: true, force: true });
test.after(removeTmp);

const APPS = ['web', 'vite', 'webpack'];
const SHARED = ['check.js', 'check-worker.js', 'check-frames.js', 'bundler/bundler.js'];
let packed;
try {
  packed = JSON.parse((await run('npm', ['pack', '--json', '--pack-destination', tmp], pkg)).stdout)[0];
  renameSync(join(tmp, packed.filename), join(tmp, 'lanepf.tgz'));
  for (const app of APPS) {
    cpSync(join(fixtures, app), join(tmp, app), { recursive: true });
    for (const f of SHARED) cpSync(join(fixtures, f), join(tmp, app, f.split('/').at(-1)));
  }
  await Promise.all(APPS.map((app) => run('npm', ['install', '--offline', '--no-audit', '--no-fund'], join(tmp, app))));
} catch (e) {
  removeTmp(); // the after hooks do not run when the set-up throws
  throw e;
}
const packedFiles = packed.files.map((f) => f.path);
// One headless Chromium for every page (start() also serves the demo, which is not used here).
// Every top-level await comes before the first test(): node:test would otherwise run the tests
// declared so far, and the after hooks, while the module is still waiting.
const env = await start();
test.after(() => env.close());

// --- the checks ------------------------------------------------------------------------------

test('the tarball holds two wasm modules, the entries, their types and the README, and nothing else', () => {
  const expected = ['README.md', 'package.json', 'web/lanepf.js', 'web/lanepf.d.ts', 'web/lanepf_bg.wasm',
    'web/lanepf_bg.wasm.d.ts', 'sim/lanepf_sim.js', 'sim/lanepf_sim.d.ts', 'sim/lanepf_sim_bg.wasm',
    'sim/lanepf_sim_bg.wasm.d.ts', 'bundler/index.js', 'bundler/index.d.ts', 'worker/index.js',
    'worker/index.d.ts', 'worker/worker.js', 'worker/serve.js', 'worker/serve.d.ts',
    'frames/index.js', 'frames/index.d.ts'];
  assert.deepEqual([...packedFiles].sort(), expected.sort());
  assert.deepEqual(packedFiles.filter((f) => f.endsWith('.wasm')).sort(), ['sim/lanepf_sim_bg.wasm', 'web/lanepf_bg.wasm']);
});

/** Asserts what every fixture reports: a rendered frame, a tracked lane, a clear error. */
function assertResult(r, where) {
  assert.ok(r && !r.failed, `${where}: ${r?.failed ?? 'no result'}`);
  assert.match(r.version, /^\d+\.\d+\.\d+/, where);
  assert.equal(r.simVersion, r.version, `${where}: lanepf/sim is the same version`);
  assert.deepEqual(r.mainHas, [], `${where}: the main module has no simulator`);
  assert.equal(r.scenarios, 12, `${where}: lanepf/sim's scenarios()`);
  assert.deepEqual([...r.ids].sort(), ['adachi-mmpf', 'danescu-mono', 'danescu-stereo', 'lee-cpf',
    'liu-ppf', 'liu-ppf-nokernel'], where);
  assert.equal(r.frame.length, 320 * 240 * 4, where);
  assert.equal(r.frame.kind, 'Uint8ClampedArray', where);
  assert.ok(r.frame.max - r.frame.min > 100, `${where}: the frame has markings and asphalt`);
  assert.ok(r.estimate.roles.includes('ego-left') && r.estimate.roles.includes('ego-right'),
    `${where}: roles ${r.estimate.roles}`);
  // The car is 0.3 m off the lane centre, so an estimate stuck at 0 fails.
  assert.ok(Math.abs(r.truth.lateral_offset_m) > 0.25, `${where}: truth ${r.truth.lateral_offset_m}`);
  const err = Math.abs(r.estimate.lateral_offset_m - r.truth.lateral_offset_m);
  assert.ok(r.estimate.valid && err < 0.15, `${where}: lee-cpf offset `
    + `${r.estimate.lateral_offset_m} m (valid ${r.estimate.valid}) vs truth ${r.truth.lateral_offset_m} m`);
  assert.ok(r.error, `${where}: new Tracker('nope') did not throw`);
  assert.ok(r.error.isError, `${where}: the thrown value is an Error`);
  assert.match(r.error.message, /nope/, where);
  for (const id of r.ids) assert.ok(r.error.message.includes(id), `${where}: ${r.error.message}`);
}

/** Serves the folder `root` alone at / (scripts/serve.mjs); returns { base, close }. */
async function serveFolder(root) {
  const server = await serve(0, root);
  return { base: `http://127.0.0.1:${server.address().port}`, close: () => server.close() };
}

/** Serves `root`, opens `page` in Chromium and returns its `window.result`, checking that every
 * request stayed on the server and a .wasm file was fetched (with `bothWasm`, exactly the two
 * modules, the main one shared by the page and its workers). */
async function resultOf(root, page, bothWasm = false) {
  const site = await serveFolder(root);
  try {
    const { page: p, errors } = await open(env.browser, 'about:blank');
    const requests = [];
    p.on('request', (r) => requests.push(r.url()));
    await p.goto(`${site.base}/${page}`);
    await p.waitForFunction(() => window.result !== undefined, null, { timeout: 60_000 })
      .catch((e) => { throw new Error(`${page}: no result (${e.message}); page errors: ${errors.join('\n')}`); });
    const result = await p.evaluate(() => window.result);
    assert.deepEqual(errors, [], `${page}: page errors`);
    assert.ok(requests.every((u) => u.startsWith(site.base) || /^(data|blob):/.test(u)), `${page}: ${requests.join(', ')}`);
    assert.ok(requests.some((u) => u.endsWith('.wasm')), `${page}: no .wasm fetched`);
    if (bothWasm) {
      const wasms = new Set(requests.filter((u) => u.endsWith('.wasm')));
      assert.equal(wasms.size, 2, `${page}: the main and the simulator's wasm for the page and its workers: ${[...wasms]}`);
    }
    await p.close();
    return result;
  } finally {
    site.close();
  }
}

/** Asserts what check-worker.js reports: the TrackerWorker matches the main thread. */
function assertWorker(r, where) {
  assert.ok(r && !r.failed, `${where}: ${r?.failed ?? 'no result'}`);
  assert.equal(r.id, 'lee-cpf', where);
  assert.ok(r.stepNames > 0, where);
  assert.deepEqual(r.same, [true, true, true, true, true, true],
    `${where}: the worker's estimates equal the main thread's`);
  assert.equal(r.detachedAfterStep, 0, `${where}: the ImageData's buffer was transferred`);
  assert.ok(r.last.valid && Math.abs(r.last.lateral_offset_m - r.truth) < 0.15,
    `${where}: ${JSON.stringify(r.last)} vs truth ${r.truth}`);
  for (const name of ['canvas', 'bitmap']) {
    const s = r.sources[name];
    assert.ok(s, `${where}: ${name} was tracked`);
    assert.equal(s.pixelDiff, 0, `${where}: ${name}: the pixels the worker saw are the frame's`);
    assert.ok(s.same, `${where}: ${name}: the estimate equals the main thread's`);
    assert.deepEqual(s.frameSize, [320, 240], where);
    assert.ok(s.hypotheses > 0 && s.hypotheses <= 5, `${where}: ${name}: ${s.hypotheses} hypotheses`);
    assert.equal(s.particles, 1000, `${where}: ${name}: the particle cloud came back (500 a stage)`);
    assert.ok(s.particlesSame, `${where}: ${name}: the cloud equals the main thread's`);
    assert.equal(s.resamplings, 2, `${where}: ${name}: lee-cpf's two stages each decided`);
    assert.ok(s.resamplingsSame, `${where}: ${name}: the resampling decisions equal the main thread's`);
    assert.ok(s.ms > 0, `${where}: ${name}: ms ${s.ms}`);
  }
  const vf = r.sources.videoFrame;
  assert.ok(vf && vf.valid && vf.pixelDiff <= 2, `${where}: VideoFrame: ${JSON.stringify(vf)}`);
  assert.equal(r.keptAfterCopy, 320 * 240 * 4, `${where}: copy: true keeps the caller's pixels`);
  assert.equal(r.resized, true, `${where}: a 640x480 canvas read at the camera's size`);
  assert.equal(r.badFrame?.name, 'LanepfInputError', `${where}: ${JSON.stringify(r.badFrame)}`);
  assert.match(r.badFrame.message, /1x1|bytes/, where);
  assert.equal(r.badOptions?.name, 'LanepfStateError', `${where}: ${JSON.stringify(r.badOptions)}`);
  assert.equal(r.badSource?.name, 'LanepfInputError', `${where}: ${JSON.stringify(r.badSource)}`);
  assert.ok(r.badFrame.isError && r.badSource.isError, where);
  assert.equal(r.afterErrors, true, `${where}: the worker still tracks after the errors`);
  assert.equal(r.badId?.name, 'LanepfConfigError', `${where}: ${JSON.stringify(r.badId)}`);
  assert.match(r.badId.message, /nope/, where);
  assert.equal(r.badConfig?.name, 'LanepfConfigError', `${where}: ${JSON.stringify(r.badConfig)}`);
  assert.ok(r.advanced.steps > 1 && r.advanced.valid !== null, `${where}: ${JSON.stringify(r.advanced)}`);
  assert.equal(r.afterTerminate?.name, 'LanepfStateError', `${where}: ${JSON.stringify(r.afterTerminate)}`);
}

/** Asserts what check-frames.js reports. */
function assertFrames(r) {
  assert.ok(r && !r.failed, r?.failed ?? 'no result');
  assert.equal(r.imageDataIdentity, true, 'an ImageData of the right size is used as it is');
  assert.deepEqual(r.imageDataScaled, { size: [32, 24], centre: [200, 200, 200] });
  assert.deepEqual(r.plainScaled, [90, 90, 90]);
  assert.deepEqual(r.canvas, { centre: [10, 200, 30], size: 64 * 48 * 4 });
  assert.deepEqual(r.bitmap, [10, 200, 30]);
  assert.deepEqual(r.img, [10, 200, 30]);
  assert.ok(r.videoFrame.every((c, i) => Math.abs(c - [10, 200, 30][i]) <= 2), `VideoFrame ${r.videoFrame}`);
  for (const key of ['closedVideoFrame', 'badSource', 'badSize', 'emptyVideo', 'readerBadSource']) {
    assert.equal(r[key]?.name, 'LanepfInputError', `${key}: ${JSON.stringify(r[key])}`);
  }
  assert.match(r.emptyVideo.message, /no frame yet/);
  assert.deepEqual(r.videoNow.size, [64, 48]);
  assert.equal(r.usesVideoFrameCallback, true);
  assert.equal(r.videoFrames.count, 4, JSON.stringify(r.videoFrames));
  assert.equal(r.videoFrames.frames, 4);
  assert.ok(r.videoFrames.timesRise, 'media times do not go back');
  for (const f of r.videoFrames.seen) {
    assert.deepEqual(f.size, [32, 24]);
    assert.equal(f.own, 32 * 24 * 4, 'each frame has a buffer of its own (transferable)');
    // Red or blue, through the video pipeline.
    const [red, , blue] = f.centre;
    assert.ok(Math.abs(red - blue) > 150, `a frame of the video: ${f.centre}`);
  }
  assert.equal(r.canvasReaderUsesVfc, false);
  assert.deepEqual(r.canvasReader, { frames: 3, failure: 'consumer failed' });
}

test('plain ES modules: an import map and init()', { timeout: 90_000 }, async () => {
  assertResult(await resultOf(join(tmp, 'web'), 'index.html'), 'plain page');
});

test('inside a module Web Worker', { timeout: 90_000 }, async () => {
  assertResult(await resultOf(join(tmp, 'web'), 'worker.html'), 'worker');
});

test('plain ES modules: lanepf/worker (TrackerWorker) and lanepf/frames', { timeout: 120_000 }, async () => {
  const r = await resultOf(join(tmp, 'web'), 'client.html', true);
  assertWorker(r.worker, 'plain TrackerWorker');
  assertFrames(r.frames);
  const c = r.custom;
  assert.ok(c && !c.failed, c?.failed ?? 'no result');
  assert.equal(c.rendered, 320 * 240 * 4, 'an op of the worker\'s own answered');
  assert.match(c.version, /^\d+\.\d+\.\d+/, 'connect() reports the version');
  assert.equal(c.idBeforeOpen, null, 'connect() opens no tracker');
  assert.equal(c.stepBeforeOpen?.name, 'LanepfStateError', JSON.stringify(c.stepBeforeOpen));
  assert.deepEqual(c.same, [true, true, true], 'the tracker in the custom worker equals the main thread\'s');
  assert.equal(c.idBefore, 'lee-cpf');
  assert.deepEqual(c.idAfter, ['adachi-mmpf', 'adachi-mmpf'], 'open() replaced the tracker in place');
  assert.ok(c.stepAfterOpen > 0);
  assert.match(c.unknownOp?.message ?? '', /unknown request 'nope'/);
  assert.equal(c.badOpen?.name, 'LanepfConfigError', JSON.stringify(c.badOpen));
  assert.equal(c.afterBadOpen?.name, 'LanepfStateError', JSON.stringify(c.afterBadOpen));
  assert.equal(c.afterClose?.name, 'LanepfStateError', JSON.stringify(c.afterClose));
});

/** Builds the Vite app with `config`; returns the output folder and vite's output. */
async function viteBuild(config, outDir) {
  const vite = join(tmp, 'vite');
  const { stdout, stderr } = await run(bin('vite'), ['build', '--config', config], vite);
  const assets = readdirSync(join(vite, outDir, 'assets'));
  assert.equal(assets.filter((f) => f.endsWith('.wasm')).length, 2, `vite emitted the two modules: ${assets}`);
  return { dist: join(vite, outDir), log: `${stdout}\n${stderr}` };
}

/** Asserts both pages of a built Vite app. */
async function assertViteApp(dist, where) {
  const r = await resultOf(dist, 'index.html');
  assertResult(r.main, `${where} main thread`);
  assertResult(r.worker, `${where} worker`);
  const b = await resultOf(dist, 'bundler.html', true);
  assertResult(b.bundler, `${where} lanepf/bundler`);
  assertWorker(b.worker, `${where} TrackerWorker`);
}

test('in a Vite app (vite build): lanepf, lanepf/bundler and lanepf/worker', { timeout: 180_000 }, async () => {
  const { dist, log } = await viteBuild('vite.config.js', 'dist');
  assert.doesNotMatch(log, /warn|\[plugin|error/i, `vite build warned:\n${log}`);
  await assertViteApp(dist, 'vite');
});

test('in a Vite app with vite-plugin-wasm (vite build)', { timeout: 180_000 }, async () => {
  const { dist } = await viteBuild('vite-plugin-wasm.config.js', 'dist-plugin');
  await assertViteApp(dist, 'vite + vite-plugin-wasm');
});

test('in a webpack 5 app: lanepf/bundler and lanepf/worker, no configuration but the entry', { timeout: 180_000 }, async () => {
  const app = join(tmp, 'webpack');
  const stats = await new Promise((resolve, reject) => {
    webpack({
      mode: 'production',
      context: app,
      entry: './bundler.js',
      output: { path: join(app, 'dist'), filename: 'main.js' },
      infrastructureLogging: { level: 'error' },
    }, (err, s) => (err ? reject(err) : resolve(s)));
  });
  const info = stats.toJson({ all: false, errors: true, warnings: true, assets: true });
  assert.deepEqual(info.errors, [], 'webpack errors');
  assert.deepEqual(info.warnings.map((w) => w.message).filter((m) => !/asset size limit|entrypoint size limit|performance/i.test(m)),
    [], 'webpack warnings (other than its size hints)');
  const emitted = info.assets.map((a) => a.name);
  assert.equal(emitted.filter((f) => f.endsWith('.wasm')).length, 2, `webpack emitted the two modules: ${emitted}`);
  cpSync(join(app, 'index.html'), join(app, 'dist', 'index.html'));
  const b = await resultOf(join(app, 'dist'), 'index.html', true);
  assertResult(b.bundler, 'webpack lanepf/bundler');
  assertWorker(b.worker, 'webpack TrackerWorker');
});

test('in a Vite app under the dev server (vite)', { timeout: 180_000 }, async () => {
  const vite = join(tmp, 'vite');
  const port = await freePort();
  const dev = spawn(bin('vite'), ['--port', String(port), '--strictPort'],
    { cwd: vite, stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, NO_COLOR: '1', FORCE_COLOR: '0' } });
  let log = '';
  dev.stdout.on('data', (d) => { log += d; });
  dev.stderr.on('data', (d) => { log += d; });
  const exited = new Promise((resolve) => dev.once('exit', resolve));
  try {
    const deadline = Date.now() + 30_000;
    // A terminal that forces colour puts escape codes between "localhost:" and the port.
    // eslint-disable-next-line no-control-regex -- ESC starts those codes
    while (!log.replace(/\x1b\[[0-9;]*m/g, '').includes(`:${port}`)) {
      if (dev.exitCode !== null || Date.now() > deadline) assert.fail(`vite did not start:\n${log}`);
      await new Promise((r) => setTimeout(r, 100));
    }
    for (const page of ['', 'bundler.html']) {
      const { page: p, errors } = await open(env.browser, `http://localhost:${port}/${page}`);
      await p.waitForFunction(() => window.result !== undefined, null, { timeout: 90_000 })
        .catch((e) => { throw new Error(`${page}: no result (${e.message}); page errors: ${errors.join('\n')}\n${log}`); });
      const r = await p.evaluate(() => window.result);
      if (page === '') {
        assertResult(r.main, 'vite dev main thread');
        assertResult(r.worker, 'vite dev worker');
      } else {
        assertResult(r.bundler, 'vite dev lanepf/bundler');
        assertWorker(r.worker, 'vite dev TrackerWorker');
      }
      assert.deepEqual(errors, [], `${page}: page errors`);
      await p.close();
    }
  } finally {
    dev.kill();
    await exited;
  }
});


/** A TCP port that was free a moment ago. */
function freePort() {
  return new Promise((resolve, reject) => {
    const s = createServer();
    s.once('error', reject);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

const tsc = (file) => run(bin('tsc'), ['--noEmit', '--strict',
  '--target', 'es2022', '--module', 'esnext', '--moduleResolution', 'bundler',
  '--lib', 'esnext,dom', file], join(tmp, 'vite'));

test('the TypeScript types accept correct use (tsc --strict)', { timeout: 90_000 }, async () => {
  cpSync(join(fixtures, 'types'), join(tmp, 'vite', 'types'), { recursive: true });
  await tsc('types/ok.ts');
});

test('the TypeScript types reject wrong configs and misread results', { timeout: 90_000 }, async () => {
  cpSync(join(fixtures, 'types'), join(tmp, 'vite', 'types'), { recursive: true });
  const source = readFileSync(join(fixtures, 'types', 'bad.ts'), 'utf8').split('\n');
  // Every line marked `// error` must be reported, and no other line.
  const expected = source.flatMap((line, i) => (/^\s*[^/\s].*\/\/ error:/.test(line) ? [i + 1] : []));
  assert.ok(expected.length >= 8, 'bad.ts marks its errors');
  const out = await tsc('types/bad.ts').then(
    () => assert.fail('tsc accepted types/bad.ts: the types are too loose'),
    (e) => e.message,
  );
  const reported = [...new Set([...out.matchAll(/bad\.ts\((\d+),\d+\): error TS\d+/g)]
    .map((m) => Number(m[1])))].sort((a, b) => a - b);
  assert.deepEqual(reported, expected, `tsc output:\n${out}`);
});
