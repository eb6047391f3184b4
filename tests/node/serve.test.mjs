// The demo server: Range requests, wasm MIME type, cross-origin isolation, no escape from www/
// and pkg/ (by name or by symbolic link), the Host check, the security headers, revalidation.
import test from 'node:test';
import assert from 'node:assert/strict';
import { request } from 'node:http';
import { serve, parseRange, resolvePath, allowedHost } from '../../scripts/serve.mjs';

test('parseRange handles open, suffix and unsatisfiable ranges', () => {
  assert.equal(parseRange(undefined, 100), null);
  assert.deepEqual(parseRange('bytes=0-9', 100), { start: 0, end: 9 });
  assert.deepEqual(parseRange('bytes=90-', 100), { start: 90, end: 99 });
  assert.deepEqual(parseRange('bytes=-10', 100), { start: 90, end: 99 });
  assert.deepEqual(parseRange('bytes=95-200', 100), { start: 95, end: 99 });
  assert.equal(parseRange('bytes=100-', 100), 'bad');
  assert.equal(parseRange('bytes=5-2', 100), 'bad');
  // RFC 9110: another unit, several ranges or a malformed one are ignored (the whole file,
  // 200), not refused with 416.
  assert.equal(parseRange('items=0-1', 100), null);
  assert.equal(parseRange('bytes=0-1,5-6', 100), null);
  assert.equal(parseRange('bytes=x-y', 100), null);
  assert.equal(parseRange('bytes=-', 100), null);
});

/** A raw GET (fetch cannot send another Host or an unnormalised path): { status, headers, body }. */
function rawGet(port, path, headers = {}) {
  return new Promise((ok, fail) => {
    request({ host: '127.0.0.1', port, path, headers }, (res) => {
      const chunks = [];
      res.on('data', (c) => chunks.push(c));
      res.on('end', () => ok({ status: res.statusCode, headers: res.headers, body: Buffer.concat(chunks).toString() }));
    }).on('error', fail).end();
  });
}

test('only localhost, 127.0.0.1 and [::1] with the port are answered (no DNS rebinding)', async () => {
  assert.ok(allowedHost('127.0.0.1:8080', 8080) && allowedHost('LOCALHOST:8080', 8080) && allowedHost('[::1]:8080', 8080));
  assert.ok(!allowedHost('127.0.0.1:8081', 8080) && !allowedHost('127.0.0.1', 8080) && !allowedHost(undefined, 8080));
  assert.ok(allowedHost('localhost', 80) && !allowedHost('evil.example:8080', 8080));
  const server = await serve(0);
  const { port } = server.address();
  try {
    assert.equal((await rawGet(port, '/index.html')).status, 200, 'Host 127.0.0.1:port');
    assert.equal((await rawGet(port, '/index.html', { Host: `localhost:${port}` })).status, 200);
    for (const host of [`attacker.example:${port}`, 'attacker.example', `127.0.0.1:${port + 1}`, `localhost.attacker.example:${port}`]) {
      const r = await rawGet(port, '/index.html', { Host: host });
      assert.equal(r.status, 421, host);
      assert.doesNotMatch(r.body, /<html/, host);
    }
  } finally {
    server.close();
  }
});

test('security headers on every response; Range units other than bytes and multiple ranges get 200', async () => {
  const server = await serve(0);
  const { port } = server.address();
  try {
    for (const path of ['/index.html', '/bench.html', '/main.js', '/nope.html', '/../Cargo.toml']) {
      const r = await rawGet(port, path);
      const csp = r.headers['content-security-policy'] ?? '';
      assert.match(csp, /script-src 'self' 'wasm-unsafe-eval'/, path);
      assert.match(csp, /frame-ancestors 'none'/, path);
      assert.equal(r.headers['x-content-type-options'], 'nosniff', path);
      assert.equal(r.headers['x-frame-options'], 'DENY', path);
    }
    const whole = await rawGet(port, '/index.html');
    for (const range of ['items=0-1', 'bytes=0-1,5-6', 'bytes=a-b']) {
      const r = await rawGet(port, '/index.html', { Range: range });
      assert.equal(r.status, 200, range);
      assert.equal(r.body, whole.body, range);
    }
    assert.equal((await rawGet(port, '/index.html', { Range: 'bytes=999999-' })).status, 416);
  } finally {
    server.close();
  }
});

test('a reload revalidates: a matching If-None-Match gets 304 without a body, another ETag the file', async () => {
  const server = await serve(0);
  const { port } = server.address();
  try {
    const whole = await rawGet(port, '/pkg/web/lanepf_bg.wasm');
    assert.equal(whole.status, 200);
    const etag = whole.headers.etag;
    assert.match(etag ?? '', /^"[0-9a-f]+-[0-9a-f]+"$/);
    assert.equal(whole.headers['cache-control'], 'no-cache');
    const again = await rawGet(port, '/pkg/web/lanepf_bg.wasm', { 'If-None-Match': etag });
    assert.equal(again.status, 304);
    assert.equal(again.body, '');
    assert.equal(again.headers.etag, etag);
    assert.match(again.headers['content-security-policy'] ?? '', /script-src 'self'/);
    assert.equal((await rawGet(port, '/pkg/web/lanepf_bg.wasm', { 'If-None-Match': `W/${etag}, "x"` })).status, 304);
    const other = await rawGet(port, '/pkg/web/lanepf_bg.wasm', { 'If-None-Match': '"0-0"' });
    assert.equal(other.status, 200);
    assert.equal(other.body, whole.body);
    // Another file has another tag.
    assert.notEqual((await rawGet(port, '/index.html')).headers.etag, etag);
  } finally {
    server.close();
  }
});

test('bench.html and index.html carry the policy themselves and have no inline style or script', async () => {
  const { readFileSync } = await import('node:fs');
  for (const page of ['index.html', 'bench.html']) {
    const html = readFileSync(new URL(`../../www/${page}`, import.meta.url), 'utf8');
    assert.match(html, /http-equiv="Content-Security-Policy" content="default-src 'self'; script-src 'self' 'wasm-unsafe-eval'/, page);
    assert.doesNotMatch(html, /<style|style="|<script(?![^>]*\bsrc=)/, page);
  }
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
  const { mkdtempSync, writeFileSync, mkdirSync, rmSync, symlinkSync } = await import('node:fs');
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
    // Symbolic links out of the root (to a file, to a folder) are refused; one inside is fine.
    const outside = mkdtempSync(join(tmpdir(), 'lanepf-outside-'));
    writeFileSync(join(outside, 'secret.txt'), 'secret');
    symlinkSync(join(outside, 'secret.txt'), join(dir, 'leak.txt'));
    symlinkSync(outside, join(dir, 'out'));
    symlinkSync(join(dir, 'index.html'), join(dir, 'home.html'));
    try {
      for (const path of ['/leak.txt', '/out/secret.txt']) {
        const r = await rawGet(server.address().port, path);
        assert.equal(r.status, 403, path);
        assert.doesNotMatch(r.body, /secret\b(?!.*link)/, path);
      }
      assert.equal((await rawGet(server.address().port, '/home.html')).body, '<p>root</p>');
    } finally {
      rmSync(outside, { recursive: true, force: true });
    }
    assert.equal(resolvePath('/sub/m.wasm', [['/', dir]]), join(dir, 'sub', 'm.wasm'));
  } finally {
    server.close();
    rmSync(dir, { recursive: true, force: true });
  }
});
