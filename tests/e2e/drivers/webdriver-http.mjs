// A small client of W3C WebDriver's classic HTTP protocol (https://www.w3.org/TR/webdriver2/),
// the few commands the end-to-end tests use, over Node's fetch. WebKitWebDriver speaks only
// this protocol here (Debian's build has no WebDriver BiDi); puppeteer-core and playwright-core
// do not drive WebKitGTK, and the general clients (selenium-webdriver, webdriver) bring a tree
// of dependencies for a dozen requests.

/** The key of an element reference in WebDriver's JSON. */
const ELEMENT = 'element-6066-11e4-a52e-4f735466cecf';

export class WebDriverSession {
  /** Creates a session on the driver at `url` (e.g. http://127.0.0.1:4444). */
  static async create(url, capabilities) {
    const value = await request(url, 'POST', '/session', { capabilities: { alwaysMatch: capabilities } });
    return new WebDriverSession(url, value.sessionId, value.capabilities);
  }

  constructor(url, id, capabilities) {
    this.url = url;
    this.id = id;
    this.capabilities = capabilities;
  }

  /** A command of this session: `path` after /session/{id}. */
  command(method, path, body) {
    return request(this.url, method, `/session/${this.id}${path}`, body);
  }

  navigate(url) { return this.command('POST', '/url', { url }); }
  refresh() { return this.command('POST', '/refresh', {}); }
  setTimeouts(timeouts) { return this.command('POST', '/timeouts', timeouts); }
  setWindowRect(rect) { return this.command('POST', '/window/rect', rect); }

  /** Runs `script` (a function body; `arguments` holds `args`, the last one the callback). */
  executeAsync(script, args = []) {
    return this.command('POST', '/execute/async', { script, args });
  }

  /** The first element matching CSS `selector` (an error when none does). */
  async find(selector) {
    const value = await this.command('POST', '/element', { using: 'css selector', value: selector });
    return value[ELEMENT];
  }

  click(element) { return this.command('POST', `/element/${element}/click`, {}); }
  sendKeys(element, text) { return this.command('POST', `/element/${element}/value`, { text }); }

  /** Input actions (keys, pointer), then releases every key and button. */
  async perform(actions) {
    await this.command('POST', '/actions', { actions });
    await this.command('DELETE', '/actions');
  }

  /** A PNG of the current page's viewport, as a Buffer. */
  async screenshot() {
    return Buffer.from(await this.command('GET', '/screenshot'), 'base64');
  }

  delete() { return request(this.url, 'DELETE', `/session/${this.id}`); }
}

/** One request; resolves to the response's `value`, or throws the driver's error. */
async function request(base, method, path, body) {
  const res = await fetch(base + path, {
    method,
    headers: body === undefined ? {} : { 'content-type': 'application/json; charset=utf-8' },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const text = await res.text();
  let json;
  try { json = JSON.parse(text); } catch { throw new Error(`WebDriver ${method} ${path}: HTTP ${res.status}: ${text.slice(0, 200)}`); }
  if (!res.ok) {
    const v = json.value ?? {};
    throw new Error(`WebDriver ${method} ${path}: ${v.error ?? res.status}: ${v.message ?? text.slice(0, 200)}`);
  }
  return json.value;
}

/** Waits until `url`/status says ready, or throws after `ms`. */
export async function waitReady(url, ms) {
  const until = Date.now() + ms;
  for (;;) {
    try {
      if ((await request(url, 'GET', '/status')).ready) return;
    } catch (e) {
      if (Date.now() > until) throw new Error(`WebDriver at ${url} not ready after ${ms} ms: ${e.message}`, { cause: e });
    }
    if (Date.now() > until) throw new Error(`WebDriver at ${url} not ready after ${ms} ms`);
    await new Promise((r) => setTimeout(r, 100));
  }
}
