// The demo server: Range requests, wasm MIME type, cross-origin isolation, no escape from www/
// and pkg/.
import test from 'node:test';
import assert from 'node:assert/strict';
import { serve, parseRange, resolvePath } from '../../scripts/serve.mjs';

test('parseRange handles open, suffix and unsatisfiable ranges', () => {
  assert.equal(parseRange(undefined, 100), null);
  assert.deepEqual(parseRange('bytes=0-9', 100), { start: 0, end: 9 });
  assert.deepEqual(parseRange('bytes=90-', 100), { start: 90, end: 99 });
  assert.deepEqual(parseRange('bytes=-10', 100), { start: 90, end: 99 });
  assert.deepEqual(parseRange('bytes=95-200', 100), { start: 95, end: 99 });
  assert.equal(parseRange('bytes=100-', 100), 'bad');
  assert.equal(parseRange('bytes=5-2', 100), 'bad');
  assert.equal(parseRange('items=0-1', 100), 'bad');
});

test('resolvePath stays inside www/ and pkg/', () => {
  assert.match(resolvePath('/index.html'), /www\/index\.html$/);
  assert.match(resolvePath('/pkg/web/lanepf.js'), /pkg\/web\/lanepf\.js$/);
  assert.equal(resolvePath('/../Cargo.toml'), null);
  assert.equal(resolvePath('/%2e%2e/Cargo.toml'), null);
  assert.equal(resolvePath('/pkg/../../etc/passwd'), null);
});

test('server answers ranges with 206 and wasm with application/wasm', async () => {
  const server = await serve(0);
  const base = `http://127.0.0.1:${server.address().port}`;
  try {
    const whole = await fetch(`${base}/index.html`);
    assert.equal(whole.status, 200);
    const text = await whole.text();
    const part = await fetch(`${base}/index.html`, { headers: { Range: 'bytes=0-14' } });
    assert.equal(part.status, 206);
    assert.equal(part.headers.get('content-range'), `bytes 0-14/${Buffer.byteLength(text)}`);
    assert.equal(await part.text(), text.slice(0, 15));
    const wasm = await fetch(`${base}/pkg/web/lanepf_bg.wasm`, { method: 'HEAD' });
    assert.equal(wasm.status, 200);
    assert.equal(wasm.headers.get('content-type'), 'application/wasm');
    // Cross-origin isolated (Firefox's clock is whole milliseconds otherwise), page and worker.
    for (const r of [whole, wasm, await fetch(`${base}/worker.js`, { method: 'HEAD' })]) {
      assert.equal(r.headers.get('cross-origin-opener-policy'), 'same-origin');
      assert.equal(r.headers.get('cross-origin-embedder-policy'), 'require-corp');
    }
    assert.equal((await fetch(`${base}/nope.html`)).status, 404);
    assert.equal((await fetch(`${base}/x`, { method: 'POST' })).status, 405);
  } finally {
    server.close();
  }
});

test('serve(port, root) serves that folder alone at /', async () => {
  const { mkdtempSync, writeFileSync, mkdirSync, rmSync } = await import('node:fs');
  const { tmpdir } = await import('node:os');
  const { join } = await import('node:path');
  const dir = mkdtempSync(join(tmpdir(), 'lanepf-serve-'));
  mkdirSync(join(dir, 'sub'));
  writeFileSync(join(dir, 'index.html'), '<p>root</p>');
  writeFileSync(join(dir, 'sub', 'm.wasm'), Buffer.from([0, 97, 115, 109]));
  const server = await serve(0, dir);
  const base = `http://127.0.0.1:${server.address().port}`;
  try {
    assert.equal(await (await fetch(`${base}/`)).text(), '<p>root</p>');
    const wasm = await fetch(`${base}/sub/m.wasm`);
    assert.equal(wasm.headers.get('content-type'), 'application/wasm');
    assert.equal((await wasm.arrayBuffer()).byteLength, 4);
    // The demo's folders are not mounted, and nothing outside the root is reachable.
    assert.equal((await fetch(`${base}/pkg/web/lanepf.js`)).status, 404);
    // fetch would normalise `..` away; send the raw path.
    const { get } = await import('node:http');
    const status = await new Promise((ok, fail) => {
      get({ host: '127.0.0.1', port: server.address().port, path: '/../etc/hostname' },
        (res) => { res.resume(); ok(res.statusCode); }).on('error', fail);
    });
    assert.equal(status, 403);
    assert.equal(resolvePath('/../x', [['/', dir]]), null);
    assert.equal(resolvePath('/sub/m.wasm', [['/', dir]]), join(dir, 'sub', 'm.wasm'));
  } finally {
    server.close();
    rmSync(dir, { recursive: true, force: true });
  }
});
