// The WebKit driver of the cross-browser end-to-end suite: Debian's WebKitGTK (WebCore and
// JavaScriptCore, Safari's engine) in its MiniBrowser on a private Xvfb display, driven by
// WebKitWebDriver over classic W3C WebDriver (webdriver-http.mjs). WebKitGTK has no headless
// mode of its own; Xvfb is the display nobody sees.
//
// Classic WebDriver reports neither page errors nor requests, so the session's HTTP proxy is a
// small recording proxy in this process: every request the browser makes (the page's, its
// workers', and any to another host, which it refuses) is logged, requests to the demo server
// are passed on, and every HTML page gets one script first in its <head>
// (/__e2e__/recorder.js) that records uncaught errors, unhandled rejections and console.error
// calls, as puppeteer's and playwright's `pageerror` and `console` events do. (Not seen:
// messages the engine itself logs, such as a refused resource.)
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import http from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { serve } from '../../../scripts/serve.mjs';
import { WebDriverSession, waitReady } from './webdriver-http.mjs';

export const name = 'WebKit';

/** The MiniBrowser of libwebkit2gtk-4.1 (its folder is named after the architecture). */
function miniBrowser() {
  if (process.env.WEBKIT_MINIBROWSER) return process.env.WEBKIT_MINIBROWSER;
  for (const arch of readdirSync('/usr/lib').filter((d) => d.endsWith('-linux-gnu'))) {
    const path = `/usr/lib/${arch}/webkit2gtk-4.1/MiniBrowser`;
    if (existsSync(path)) return path;
  }
  throw new Error('WebKitGTK MiniBrowser not found (apt-get install webkit2gtk-driver; scripts/setup.sh does)');
}

const RECORDER_PATH = '/__e2e__/recorder.js';
const RECORDER = `(() => {
  const errors = (window.__e2eErrors = []);
  addEventListener('error', (e) => errors.push('pageerror: ' + e.message));
  addEventListener('unhandledrejection', (e) => errors.push('pageerror: ' + (e.reason?.message ?? e.reason)));
  const original = console.error;
  console.error = function (...args) {
    errors.push('console: ' + args.map(String).join(' '));
    return original.apply(this, args);
  };
})();
`;

/** The recording proxy in front of the demo server at `target` (host:port); logs to `log`. */
function recordingProxy(target, log) {
  const [host, port] = target.split(':');
  const proxy = http.createServer((req, res) => {
    log.push(req.url);
    let url = null;
    try { url = new URL(req.url); } catch { /* not a proxy request */ }
    if (!url || url.host !== target) {
      res.writeHead(502).end('the end-to-end tests allow no request beyond the demo server\n');
      return;
    }
    if (url.pathname === RECORDER_PATH) {
      res.writeHead(200, { 'content-type': 'text/javascript; charset=utf-8' }).end(RECORDER);
      return;
    }
    const headers = { ...req.headers };
    delete headers['proxy-connection'];
    const upstream = http.request({ host, port, method: req.method, path: url.pathname + url.search, headers }, (up) => {
      if (!/^text\/html/.test(up.headers['content-type'] ?? '')) {
        res.writeHead(up.statusCode, up.headers);
        up.pipe(res);
        return;
      }
      const chunks = [];
      up.on('data', (c) => chunks.push(c));
      up.on('end', () => {
        const html = Buffer.concat(chunks).toString('utf8')
          .replace(/<head>/i, `<head><script src="${RECORDER_PATH}"></script>`);
        const body = Buffer.from(html, 'utf8');
        res.writeHead(up.statusCode, { ...up.headers, 'content-length': body.length }).end(body);
      });
    });
    upstream.on('error', () => res.destroy());
    req.pipe(upstream);
  });
  // https: recorded and refused.
  proxy.on('connect', (req, socket) => {
    log.push(`https://${req.url}/`);
    socket.end('HTTP/1.1 502 Bad Gateway\r\n\r\n');
  });
  return new Promise((ok) => proxy.listen(0, '127.0.0.1', () => ok(proxy)));
}

/** A free TCP port on 127.0.0.1 (for WebKitWebDriver, which takes a port number). */
function freePort() {
  return new Promise((ok, fail) => {
    const s = http.createServer();
    s.once('error', fail);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => ok(port));
    });
  });
}

/** Starts Xvfb on the first free display; resolves to { display, process }. */
function startXvfb() {
  return new Promise((ok, fail) => {
    // -displayfd: Xvfb picks a free display and writes its number to fd 3.
    const xvfb = spawn('Xvfb', ['-displayfd', '3', '-screen', '0', '1280x1024x24', '-nolisten', 'tcp'],
      { stdio: ['ignore', 'ignore', 'pipe', 'pipe'] });
    let out = '';
    let err = '';
    xvfb.stderr.on('data', (d) => { err += d; });
    xvfb.stdio[3].on('data', (d) => {
      out += d;
      if (out.includes('\n')) ok({ display: `:${out.trim()}`, process: xvfb });
    });
    xvfb.once('error', (e) => fail(new Error(`cannot start Xvfb (apt-get install xvfb): ${e.message}`)));
    xvfb.once('exit', (code) => fail(new Error(`Xvfb exited (${code}): ${err.slice(-500)}`)));
  });
}

/** Starts the demo server, Xvfb, WebKitWebDriver and a MiniBrowser session. */
export async function launch() {
  const server = await serve(0);
  const base = `http://127.0.0.1:${server.address().port}`;
  const requests = [];
  const proxy = await recordingProxy(`127.0.0.1:${server.address().port}`, requests);
  const xvfb = await startXvfb();
  // A home of its own: a fresh profile, nothing written to the user's.
  const home = mkdtempSync(join(tmpdir(), 'lanepf-webkit-'));
  const port = await freePort();
  const driver = spawn('WebKitWebDriver', [`--port=${port}`], {
    detached: true, // its own process group, with the browser it starts: killed as one
    stdio: ['ignore', 'ignore', 'pipe'],
    env: {
      ...process.env, DISPLAY: xvfb.display, HOME: home, XDG_CONFIG_HOME: join(home, 'config'),
      XDG_CACHE_HOME: join(home, 'cache'), XDG_DATA_HOME: join(home, 'data'), XDG_RUNTIME_DIR: home,
    },
  });
  let driverLog = '';
  driver.stderr.on('data', (d) => { driverLog = (driverLog + d).slice(-4000); });
  const kill = () => {
    try { process.kill(-driver.pid, 'SIGKILL'); } catch { /* already gone */ }
    xvfb.process.kill('SIGKILL');
  };
  // (Also when the test runner stops this process with a signal: the driver's process group
  // is its own, so it would outlive this one.)
  const onSignal = (signal) => {
    kill();
    process.kill(process.pid, signal);
  };
  process.once('exit', kill);
  process.once('SIGINT', onSignal);
  process.once('SIGTERM', onSignal);
  const url = `http://127.0.0.1:${port}`;
  let session;
  try {
    await waitReady(url, 20_000);
    const proxyAt = `127.0.0.1:${proxy.address().port}`;
    session = await WebDriverSession.create(url, {
      proxy: { proxyType: 'manual', httpProxy: proxyAt, sslProxy: proxyAt },
      'webkitgtk:browserOptions': {
        binary: miniBrowser(),
        args: ['--automation',
          // The webcam: WebKit's mock camera (a moving test picture), granted without a prompt.
          '--enable-media-stream=true', '--enable-mock-capture-devices=true',
          // No GPU here: an accelerated 2D canvas runs on Mesa's software GL in Xvfb, where
          // each putImageData of the demo's frame costs ~25 ms (0.1 ms unaccelerated) and the
          // demo plays at 3 frames/s on a synthetic scene (9 unaccelerated; Firefox 21). The
          // compositor stays accelerated, as in Safari: without it WebKitGTK never calls
          // requestVideoFrameCallback (~20 frames/s, but a video's rate cannot be measured).
          '--enable-2d-canvas-acceleration=false',
          // More MiniBrowser options for a diagnosis, e.g. WEBKIT_ARGS=--enable-webgl=false.
          ...(process.env.WEBKIT_ARGS?.split(' ').filter(Boolean) ?? [])],
      },
    });
    await session.setTimeouts({ script: 120_000, pageLoad: 60_000 });
    await session.setWindowRect({ x: 0, y: 0, width: 1280, height: 1000 });
  } catch (e) {
    kill();
    throw new Error(`${e.message}\nWebKitWebDriver said: ${driverLog}`, { cause: e });
  }
  return {
    name,
    version: `WebKitGTK ${session.capabilities.browserVersion}`,
    base,
    /** Opens `url`; a page records the errors and requests from then on. */
    async open(pageUrl) {
      const page = new WebKitPage(session, requests);
      await session.navigate(pageUrl);
      return page;
    },
    async close() {
      await session.delete().catch(() => {});
      kill();
      process.removeListener('exit', kill);
      process.removeListener('SIGINT', onSignal);
      process.removeListener('SIGTERM', onSignal);
      proxy.close();
      server.close();
      rmSync(home, { recursive: true, force: true });
    },
  };
}

/** The page: the session's one window (the tests open one page at a time). */
class WebKitPage {
  constructor(session, requests) {
    this.session = session;
    this.allRequests = requests;
    this.firstRequest = requests.length;
    this.seenErrors = [];
  }

  /** Keeps the errors the current document recorded before it goes away. */
  async harvest() {
    const errs = await this.eval(() => window.__e2eErrors ?? []).catch(() => []);
    this.seenErrors.push(...errs);
  }

  async goto(url) {
    await this.harvest();
    await this.session.navigate(url);
  }

  async reload() {
    await this.harvest();
    await this.session.refresh();
  }

  /** Runs `fn(...args)` in the page (it may be async) and resolves to its JSON value. */
  async eval(fn, ...args) {
    const r = await this.session.executeAsync(`const done = arguments[arguments.length - 1];
      Promise.resolve().then(() => (${fn})(...arguments[0]))
        .then((v) => done({ ok: v === undefined ? null : v }), (e) => done({ thrown: String(e) + '\\n' + (e?.stack ?? '') }));`, [args]);
    if (r && 'thrown' in r) throw new Error(`in the page: ${r.thrown}`);
    return r.ok;
  }

  /** Waits until `fn(arg)` is truthy in the page (polled every 100 ms). */
  async waitFor(fn, { arg, timeout = 30_000 } = {}) {
    const until = Date.now() + timeout;
    for (;;) {
      const v = await this.eval(fn, arg);
      if (v) return v;
      if (Date.now() > until) throw new Error(`timed out after ${timeout} ms waiting for ${fn}`);
      await new Promise((r) => setTimeout(r, 100));
    }
  }

  async click(selector) {
    await this.session.click(await this.session.find(selector));
  }

  /** Chooses `value` in <select> `selector` as puppeteer's page.select does (input and change events). */
  async select(selector, value) {
    await this.eval((selector, value) => {
      const s = document.querySelector(selector);
      s.value = value;
      s.dispatchEvent(new Event('input', { bubbles: true }));
      s.dispatchEvent(new Event('change', { bubbles: true }));
    }, selector, value);
  }

  /** Sets files (paths on disk) on <input type=file> `selector`, as a person picking them. */
  async setFiles(selector, paths) {
    await this.session.sendKeys(await this.session.find(selector), paths.join('\n'));
  }

  /** Presses and releases one key (' ', '.', ...). */
  async press(key) {
    await this.session.perform([{ type: 'key', id: 'keyboard', actions: [
      { type: 'keyDown', value: key }, { type: 'keyUp', value: key }] }]);
  }

  /** Clicks at viewport point (x, y). */
  async clickAt(x, y) {
    await this.pointer([{ type: 'pointerMove', x: Math.round(x), y: Math.round(y), origin: 'viewport' },
      { type: 'pointerDown', button: 0 }, { type: 'pointerUp', button: 0 }]);
  }

  /** Drags the mouse from viewport point `from` to `to` in `steps` moves. */
  async drag(from, to, steps = 4) {
    const at = (k) => ({ type: 'pointerMove', origin: 'viewport', duration: 20,
      x: Math.round(from[0] + (to[0] - from[0]) * k / steps), y: Math.round(from[1] + (to[1] - from[1]) * k / steps) });
    await this.pointer([{ ...at(0), duration: 0 }, { type: 'pointerDown', button: 0 },
      ...Array.from({ length: steps }, (_, k) => at(k + 1)), { type: 'pointerUp', button: 0 }]);
  }

  pointer(actions) {
    return this.session.perform([{ type: 'pointer', id: 'mouse', parameters: { pointerType: 'mouse' }, actions }]);
  }

  async screenshot(path) {
    writeFileSync(path, await this.session.screenshot());
  }

  /** Page errors and console errors since the page was opened. */
  async errors() {
    const now = await this.eval(() => window.__e2eErrors ?? []);
    return [...this.seenErrors, ...now];
  }

  /** URLs the browser requested since the page was opened. */
  requests() {
    return this.allRequests.slice(this.firstRequest);
  }

  /** Leaves the page (its workers and camera stop). */
  async close() {
    await this.session.navigate('about:blank');
  }
}
