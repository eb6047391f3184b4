// The npm package as users get it: `npm pack` of pkg/ (after `make pkg`), installed from the
// tarball into small apps in a temporary folder, each run in headless Chromium:
//   web/index.html   plain ES modules with an import map (no bundler)
//   web/worker.html  the package inside a module Web Worker
//   vite/            a Vite app with no configuration, on the main thread and in a worker it
//                    bundles: built (`vite build`) and served, and under the dev server (`vite`)
// and its TypeScript types: a correct program must pass `tsc --strict`, and a program with
// deliberate type errors must fail on exactly the lines that have them. Vite and TypeScript come
// from the npm registry at the versions pinned in fixtures/vite/package.json; when the registry
// cannot be reached the test fails (it never skips).
import test from 'node:test';
import assert from 'node:assert/strict';
import { execFile, spawn } from 'node:child_process';
import { createServer } from 'node:net';
import { cpSync, existsSync, mkdtempSync, readdirSync, readFileSync, renameSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { start, open } from '../e2e/browser.mjs';
import { serve } from '../../scripts/serve.mjs';

const here = fileURLToPath(new URL('.', import.meta.url));
const repo = join(here, '..', '..');
const pkg = join(repo, 'pkg');
const fixtures = join(here, 'fixtures');

/** Runs a command; rejects with its output when it fails or takes longer than `timeout` ms. */
function run(cmd, args, cwd, timeout = 120_000) {
  return new Promise((resolve, reject) => {
    execFile(cmd, args, { cwd, timeout, maxBuffer: 16 << 20 }, (err, stdout, stderr) => {
      if (err) {
        reject(new Error(`\`${cmd} ${args.join(' ')}\` in ${cwd} failed (${err.code ?? err.signal}):\n`
          + `${stdout}\n${stderr}`));
      } else {
        resolve({ stdout, stderr });
      }
    });
  });
}

const npmInstall = (dir) => run('npm', ['install', '--no-audit', '--no-fund'], dir).catch((e) => {
  throw new Error(`npm install failed: the npm test needs the npm registry for the fixture apps `
    + `(vite, typescript).\n${e.message}`);
});

// --- set-up: pack, copy the fixtures, install ------------------------------------------------

assert.ok(existsSync(join(pkg, 'web', 'lanepf_bg.wasm')),
  'pkg/web/lanepf_bg.wasm is missing: run `make pkg` first');
const tmp = mkdtempSync(join(tmpdir(), 'lanepf-npm-'));
const removeTmp = () => rmSync(tmp, { recursive: true, force: true });
test.after(removeTmp);

let packedFiles;
try {
  const packed = JSON.parse((await run('npm', ['pack', '--json', '--pack-destination', tmp], pkg)).stdout);
  packedFiles = packed[0].files.map((f) => f.path);
  renameSync(join(tmp, packed[0].filename), join(tmp, 'lanepf.tgz'));
  for (const app of ['web', 'vite']) {
    cpSync(join(fixtures, app), join(tmp, app), { recursive: true });
    cpSync(join(fixtures, 'check.js'), join(tmp, app, 'check.js'));
  }
  await Promise.all([npmInstall(join(tmp, 'web')), npmInstall(join(tmp, 'vite'))]);
} catch (e) {
  removeTmp(); // the after hooks do not run when the set-up throws
  throw e;
}
// One headless Chromium for every page (start() also serves the demo, which is not used here).
// Every top-level await comes before the first test(): node:test would otherwise run the tests
// declared so far, and the after hooks, while the module is still waiting.
const env = await start();
test.after(() => env.close());

// --- the checks ------------------------------------------------------------------------------

test('the tarball holds both targets, their types and the README, and nothing else', () => {
  for (const f of ['web/lanepf.js', 'web/lanepf.d.ts', 'web/lanepf_bg.wasm', 'bundler/lanepf.js',
    'bundler/lanepf_bg.wasm', 'README.md', 'package.json']) {
    assert.ok(packedFiles.includes(f), `${f} is in the tarball (${packedFiles.join(', ')})`);
  }
  assert.ok(packedFiles.every((f) => /^(web|bundler)\/|^README\.md$|^package\.json$/.test(f)),
    `unexpected files: ${packedFiles.join(', ')}`);
});

/** Asserts what every fixture reports: a rendered frame, a tracked lane, a clear error. */
function assertResult(r, where) {
  assert.ok(r && !r.failed, `${where}: ${r?.failed ?? 'no result'}`);
  assert.match(r.version, /^\d+\.\d+\.\d+/, where);
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
 * request stayed on the server and a .wasm file was fetched. */
async function resultOf(root, page) {
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
    assert.ok(requests.every((u) => u.startsWith(site.base) || u.startsWith('data:')), `${page}: ${requests.join(', ')}`);
    assert.ok(requests.some((u) => u.endsWith('.wasm')), `${page}: no .wasm fetched`);
    await p.close();
    return result;
  } finally {
    site.close();
  }
}

test('plain ES modules: an import map and init()', { timeout: 90_000 }, async () => {
  assertResult(await resultOf(join(tmp, 'web'), 'index.html'), 'plain page');
});

test('inside a module Web Worker', { timeout: 90_000 }, async () => {
  assertResult(await resultOf(join(tmp, 'web'), 'worker.html'), 'worker');
});

test('in a Vite app (vite build), on the main thread and in a worker', { timeout: 120_000 }, async () => {
  const vite = join(tmp, 'vite');
  await run(join(vite, 'node_modules', '.bin', 'vite'), ['build'], vite);
  const assets = readdirSync(join(vite, 'dist', 'assets'));
  assert.ok(assets.some((f) => f.endsWith('.wasm')), `vite emitted the wasm: ${assets}`);
  const r = await resultOf(join(vite, 'dist'), 'index.html');
  assertResult(r.main, 'vite main thread');
  assertResult(r.worker, 'vite worker');
});

test('in a Vite app under the dev server (vite, no configuration)', { timeout: 90_000 }, async () => {
  const vite = join(tmp, 'vite');
  const port = await freePort();
  const dev = spawn(join(vite, 'node_modules', '.bin', 'vite'), ['--port', String(port), '--strictPort'],
    { cwd: vite, stdio: ['ignore', 'pipe', 'pipe'], env: { ...process.env, NO_COLOR: '1', FORCE_COLOR: '0' } });
  let log = '';
  dev.stdout.on('data', (d) => { log += d; });
  dev.stderr.on('data', (d) => { log += d; });
  const exited = new Promise((resolve) => dev.once('exit', resolve));
  try {
    const deadline = Date.now() + 30_000;
    // A terminal that forces colour puts escape codes between "localhost:" and the port.
    while (!log.replace(/\x1b\[[0-9;]*m/g, '').includes(`:${port}`)) {
      if (dev.exitCode !== null || Date.now() > deadline) assert.fail(`vite did not start:\n${log}`);
      await new Promise((r) => setTimeout(r, 100));
    }
    const { page, errors } = await open(env.browser, `http://localhost:${port}/`);
    await page.waitForFunction(() => window.result !== undefined, null, { timeout: 60_000 })
      .catch((e) => { throw new Error(`no result (${e.message}); page errors: ${errors.join('\n')}`); });
    const r = await page.evaluate(() => window.result);
    assertResult(r.main, 'vite dev main thread');
    assertResult(r.worker, 'vite dev worker');
    assert.deepEqual(errors, [], 'page errors');
    await page.close();
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

const tsc = (file) => run(join(tmp, 'vite', 'node_modules', '.bin', 'tsc'), ['--noEmit', '--strict',
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
