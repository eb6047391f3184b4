// The Chromium driver of the cross-browser end-to-end suite: Debian's headless Chromium driven
// by playwright-core (browser.mjs), with its fake camera granted without a prompt. The same
// page operations as firefox.mjs and webkit.mjs.
import { start } from '../browser.mjs';
import { EventPage } from './event-page.mjs';

export const name = 'Chromium';

/** Starts the server and headless Chromium. */
export async function launch() {
  const env = await start(['--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream']);
  return {
    name,
    version: `Chromium ${env.browser.version()}`,
    base: env.base,
    /** Opens `url` in a new page that records page errors, console errors and requests. */
    async open(url) {
      const page = new ChromiumPage(await env.browser.newPage());
      await page.page.goto(url);
      return page;
    },
    close: () => env.close(),
  };
}

class ChromiumPage extends EventPage {
  /** Runs `fn(...args)` in the page (it may be async) and resolves to its value. */
  eval(fn, ...args) {
    // (playwright passes one argument, so the call goes as an expression; arguments are JSON.)
    return this.page.evaluate(`(${fn})(...${JSON.stringify(args)})`);
  }
  /** Waits until `fn(arg)` is truthy in the page; resolves to that value. */
  async waitFor(fn, { arg, timeout = 30_000 } = {}) {
    return EventPage.valueOf(await this.page.waitForFunction(fn, arg, { timeout }));
  }
  async select(selector, value) { await this.page.selectOption(selector, value); }
  /** Sets files (paths on disk) on <input type=file> `selector`. */
  setFiles(selector, paths) { return this.page.setInputFiles(selector, paths); }
}
