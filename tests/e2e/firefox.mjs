// Shared set-up for the Firefox end-to-end test: the demo server and Debian's Firefox ESR,
// driven over WebDriver BiDi by puppeteer-core (playwright-core's Firefox is Playwright's own
// patched build, which is a download; this drives the browser apt installed).
import puppeteer from 'puppeteer-core';
import { serve } from '../../scripts/serve.mjs';

export const FIREFOX = process.env.FIREFOX ?? '/usr/bin/firefox-esr';

// The network here is closed (and a test should not phone home anyway): no updates, telemetry,
// captive-portal or connectivity probes, remote settings, safe-browsing lists, prefetching.
// puppeteer's own profile already turns off some of these; they are repeated so that this
// list alone says what the test relies on.
const PREFS = {
  'app.update.auto': false,
  'app.update.enabled': false,
  'app.update.disabledForTesting': true,
  'app.normandy.enabled': false,
  'app.normandy.api_url': '',
  'app.shield.optoutstudies.enabled': false,
  'browser.discovery.enabled': false,
  'browser.newtabpage.enabled': false,
  'browser.ping-centre.telemetry': false,
  'browser.region.network.url': '',
  'browser.region.update.enabled': false,
  'browser.safebrowsing.downloads.remote.enabled': false,
  'browser.safebrowsing.malware.enabled': false,
  'browser.safebrowsing.phishing.enabled': false,
  'browser.safebrowsing.provider.google4.updateURL': '',
  'browser.safebrowsing.provider.mozilla.updateURL': '',
  'browser.search.update': false,
  'browser.shell.checkDefaultBrowser': false,
  'browser.startup.page': 0,
  'datareporting.healthreport.uploadEnabled': false,
  'datareporting.policy.dataSubmissionEnabled': false,
  'extensions.getAddons.cache.enabled': false,
  'extensions.update.enabled': false,
  'media.gmp-manager.updateEnabled': false,
  'messaging-system.rsexperimentloader.enabled': false,
  'network.captive-portal-service.enabled': false,
  'network.connectivity-service.enabled': false,
  'network.dns.disablePrefetch': true,
  'network.http.speculative-parallel-limit': 0,
  'network.prefetch-next': false,
  'services.settings.server': 'http://127.0.0.1:1/',
  'toolkit.telemetry.enabled': false,
  'toolkit.telemetry.server': '',
  'toolkit.telemetry.unified': false,
  // The webcam: Firefox's fake camera (a test picture), granted without a prompt.
  'media.navigator.streams.fake': true,
  'media.navigator.permission.disabled': true,
};

/** Starts the server and headless Firefox (a fresh temporary profile); returns { base, browser, close }. */
export async function startFirefox() {
  const server = await serve(0);
  const base = `http://127.0.0.1:${server.address().port}`;
  const browser = await puppeteer.launch({
    browser: 'firefox', executablePath: FIREFOX, headless: true, extraPrefsFirefox: PREFS,
    // Firefox's headless mode also reads MOZ_HEADLESS; no display is needed either way.
    env: { ...process.env, MOZ_HEADLESS: '1' },
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

/** Opens `url` in a new tab that records page errors and console errors. */
export async function openFirefox(browser, url) {
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(`pageerror: ${e.message}`));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  await page.goto(url);
  return { page, errors };
}
