// The part of a driver's page that puppeteer-core (Firefox) and playwright-core (Chromium) share:
// their pages report errors and requests as events and have the same mouse, keyboard, click,
// screenshot and close. Each driver adds eval, waitFor, select and setFiles in its library's
// words.

export class EventPage {
  constructor(page) {
    this.page = page;
    this.errorList = [];
    this.requestList = [];
    page.on('pageerror', (e) => this.errorList.push(`pageerror: ${e.message}`));
    page.on('console', (m) => { if (m.type() === 'error') this.errorList.push(`console: ${m.text()}`); });
    page.on('request', (r) => this.requestList.push(r.url()));
  }

  goto(url) { return this.page.goto(url); }
  reload() { return this.page.reload(); }
  click(selector) { return this.page.click(selector); }
  press(key) { return this.page.keyboard.press(key); }
  clickAt(x, y) { return this.page.mouse.click(x, y); }
  /** Drags the mouse from viewport point `from` to `to` in `steps` moves. */
  async drag(from, to, steps = 4) {
    await this.page.mouse.move(...from);
    await this.page.mouse.down();
    await this.page.mouse.move(...to, { steps });
    await this.page.mouse.up();
  }
  screenshot(path) { return this.page.screenshot({ path, fullPage: true }); }
  /** Page errors and console errors since the page was opened. */
  async errors() { return this.errorList; }
  /** URLs the page requested since it was opened. */
  requests() { return this.requestList; }
  close() { return this.page.close(); }

  /** The value of a wait's handle (both libraries resolve waitForFunction to a handle). */
  static async valueOf(handle) {
    const value = await handle.jsonValue();
    await handle.dispose();
    return value;
  }
}
