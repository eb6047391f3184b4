// Shared set-up for the browser end-to-end tests: the demo server and Debian's headless Chromium
// driven by playwright-core (never a downloaded browser; see ../shared/TOOLCHAIN.md).
import { chromium } from 'playwright-core';
import { serve } from '../../scripts/serve.mjs';

export const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';
const ARGS = [
  '--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--disable-background-networking',
  '--disable-component-update', '--disable-sync', '--disable-quic', '--no-first-run',
];

/** Starts the server and the browser (with `extraArgs`); returns { base, browser, close }. */
export async function start(extraArgs = []) {
  const server = await serve(0);
  const base = `http://127.0.0.1:${server.address().port}`;
  const browser = await chromium.launch({
    executablePath: CHROMIUM, headless: true, args: [...ARGS, ...extraArgs],
  });
  return {
    base,
    browser,
    async close() {
      await browser.close();
      server.close();
    },
  };
}

/**
 * Opens `url` in a new page that records page errors, console errors and the package's
 * deprecation warnings (the demo must not use a deprecated call, workers included).
 */
export async function open(browser, url, contextOptions = {}) {
  const page = await browser.newPage(contextOptions);
  const errors = [];
  page.on('pageerror', (e) => errors.push(`pageerror: ${e.message}`));
  const deprecated = (m) => {
    if (m.type() === 'warning' && /lanepf: .*deprecated/.test(m.text())) errors.push(`deprecated: ${m.text()}`);
  };
  page.on('console', (m) => {
    if (m.type() === 'error') errors.push(`console: ${m.text()}`);
    deprecated(m);
  });
  page.on('worker', (w) => w.on('console', deprecated));
  await page.goto(url);
  return { page, errors };
}

/** Waits until the demo page has started (`document.body.dataset.state` is `running`). */
export const running = (page) => page.waitForFunction(() => document.body.dataset.state === 'running',
  null, { timeout: 30000 });

/** Waits until the demo page has no action queued or in flight (`lanepfDemo.pending` is 0). */
export const idle = (page) => page.waitForFunction(() => window.lanepfDemo.pending === 0, null, { timeout: 30000 });
