// End-to-end in every browser, one suite over a list of drivers (drivers/chromium.mjs: Debian's
// Chromium with playwright-core; drivers/firefox.mjs: Debian's Firefox ESR over WebDriver BiDi;
// drivers/webkit.mjs: WebKitGTK, Safari's engine, over classic WebDriver), each exposing the
// same page operations. The same checks and thresholds in each, and no page errors: the
// bundled clip tracked and drawn; the test road under its ground truth; every tracker on a
// synthetic scene within 0.3 m with a clock finer than whole milliseconds; an uploaded video
// read to its end (with WebCodecs, or by seeking at its measured rate), undecodable files
// explained; an image sequence with an imported camera; the webcam (the browser's fake
// camera); the calibration helper's drag; bench.html and its bad parameters; a refused camera
// permission; the keyboard; the per-step mode stage by stage; two trackers side by side;
// export; the teaching panel; stereo input. Only in Chromium (the other files): the npm
// package's fixture apps, the real download of an export, scenario switching, tracker cue
// views, danescu's marking bands, bad camera fields, sources.test.mjs and webcodecs.test.mjs.
//   E2E_BROWSERS=webkit node --test tests/e2e/cross-browser.test.mjs   runs one browser
import { describe, test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, mkdtempSync, writeFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import * as chromium from './drivers/chromium.mjs';
import * as firefox from './drivers/firefox.mjs';
import * as webkit from './drivers/webkit.mjs';
import { readCanvas, lum, peak, countColour, countNear } from './pixels.mjs';

const ALL = [chromium, firefox, webkit];
const wanted = process.env.E2E_BROWSERS?.split(',') ?? ALL.map((d) => d.name.toLowerCase());
const unknown = wanted.filter((w) => !ALL.some((d) => d.name.toLowerCase() === w));
if (unknown.length) throw new Error(`E2E_BROWSERS: no driver ${unknown.join(', ')} (chromium, firefox, webkit)`);
const DRIVERS = ALL.filter((d) => wanted.includes(d.name.toLowerCase()));
const CLIP = fileURLToPath(new URL('../../www/clips/udacity-project-640x360.webm', import.meta.url));
// Which browsers' VideoDecoder takes the bundled clip's VP9 (the page then reads videos with
// WebCodecs; otherwise by seeking a <video>): WebKitGTK's, with Debian's GStreamer plugins, not.
const WEBCODECS_VP9 = { Chromium: true, Firefox: true, WebKit: false };
const TRACKERS = ['adachi-mmpf', 'danescu-mono', 'danescu-stereo', 'lee-cpf', 'liu-ppf', 'liu-ppf-nokernel'];
mkdirSync('test-results', { recursive: true });

// Page helpers over the drivers' common operations.
const text = (page, selector) => page.eval((s) => document.querySelector(s).textContent, selector);
const visible = (page, selector) => page.eval((s) => document.querySelector(s).checkVisibility(), selector);
const enabled = (page, selector) => page.eval((s) => !document.querySelector(s).disabled, selector);
const demo = (page, key) => page.eval((k) => window.lanepfDemo[k], key);
/** Waits for the page's data-state `state`; a timeout says the state and status line instead. */
const pageState = async (page, state, timeout = 30_000) => {
  try {
    await page.waitFor((s) => document.body.dataset.state === s, { arg: state, timeout });
  } catch (e) {
    const now = await page.eval(() => `${document.body.dataset.state}: ${document.getElementById('status')?.textContent}`)
      .catch(() => 'unknown');
    throw new Error(`the page did not reach state ${state} in ${timeout} ms (it is ${now})`, { cause: e });
  }
};
const running = (page) => pageState(page, 'running');
const framesAtLeast = (page, n, timeout = 30_000) => page.waitFor((n) => window.lanepfDemo.frames >= n, { arg: n, timeout });
const idle = (page) => page.waitFor(() => window.lanepfDemo.pending === 0);
/** Sets checkbox `selector` to `on` with a click, as a person would. */
const setChecked = async (page, selector, on) => {
  if (await page.eval((s) => document.querySelector(s).checked, selector) !== on) await page.click(selector);
};
/** Opens the "Your own media" disclosure (stereo, camera file), as a person would. */
const openAdvanced = async (page) => {
  if (!await page.eval(() => document.getElementById('advanced').open)) await page.click('#advanced summary');
};
/** Types `value` into input `selector` and lets go of it (its change event). */
const setValue = (page, selector, value) => page.eval((s, v) => {
  const i = document.querySelector(s);
  i.value = v;
  i.dispatchEvent(new Event('input', { bubbles: true }));
  i.dispatchEvent(new Event('change', { bubbles: true }));
}, selector, value);
/** PNG files (base64) of frames of a simulator scene, made in the page by the simulator's module. */
const scenePngs = (page, scenario, seed, frames, stereo = false) => page.eval(async (scenario, seed, frames, stereo) => {
  const m = await import('/pkg/sim/lanepf_sim.js');
  await m.default();
  const scene = new m.Scene(scenario, { width: 640, height: 480, seed });
  const png = async (parts) => {
    const canvas = new OffscreenCanvas(640 * parts.length, 480);
    parts.forEach((rgba, k) => canvas.getContext('2d').putImageData(new ImageData(rgba, 640, 480), 640 * k, 0));
    const bytes = new Uint8Array(await (await canvas.convertToBlob({ type: 'image/png' })).arrayBuffer());
    let s = '';
    for (const b of bytes) s += String.fromCharCode(b);
    return btoa(s);
  };
  const out = { left: [], right: [], sbs: [] };
  for (let f = 0; f < frames; f++) {
    const l = scene.render(f);
    out.left.push(await png([l]));
    if (stereo) {
      const r = scene.renderRight(f);
      out.right.push(await png([r]));
      out.sbs.push(await png([l, r]));
    }
  }
  return { ...out, camera: scene.camera(), truth: scene.truth(frames - 1).lateral_offset_m };
}, scenario, seed, frames, stereo);
/** Replaces the download of a Blob through an <a download> click with a record in the page
 * (window.__downloads: name, type, text): classic WebDriver cannot fetch downloads, so every
 * browser here is checked the same way; Chromium's suite checks the real download. */
const captureDownloads = (page) => page.eval(() => {
  const blobs = new Map();
  const create = URL.createObjectURL;
  URL.createObjectURL = (b) => {
    const url = create.call(URL, b);
    blobs.set(url, b);
    return url;
  };
  window.__downloads = [];
  const click = HTMLAnchorElement.prototype.click;
  HTMLAnchorElement.prototype.click = function () {
    const blob = this.download ? blobs.get(this.href) : undefined;
    if (!blob) return click.call(this);
    const entry = { name: this.download, type: blob.type, text: null };
    window.__downloads.push(entry);
    blob.text().then((t) => { entry.text = t; });
  };
});

for (const driver of DRIVERS) {
  describe(driver.name, () => {
    let b; // the browser: { name, version, base, open, close }
    let files; // a folder for the files handed to file inputs
    before(async () => {
      b = await driver.launch();
      files = mkdtempSync(join(tmpdir(), `lanepf-${driver.name.toLowerCase()}-`));
      console.log(`${driver.name}: ${b.version}`);
    });
    after(async () => {
      await b?.close();
      rmSync(files, { recursive: true, force: true });
    });
    const N = driver.name;
    const writeFile = (name, content) => {
      const path = join(files, name);
      writeFileSync(path, content);
      return path;
    };

    test(`${N}: the driver sees page errors, console errors and requests to other hosts`, async () => {
      // (What makes the other tests' "no errors" and "no foreign requests" checks mean something.)
      const page = await b.open(`${b.base}/bench.html?frames=6&warmup=5&width=64&height=48`);
      await page.waitFor(() => window.lanepfBench?.done);
      await page.eval(() => {
        console.error('a console error');
        setTimeout(() => { throw new Error('an uncaught error'); });
        // The page's Content-Security-Policy refuses other hosts: Chromium's driver still sees
        // the refused request, Firefox's and WebKit's never see it leave, so the page notes
        // the refusal itself.
        window.cspRefused = [];
        document.addEventListener('securitypolicyviolation', (e) => window.cspRefused.push(e.blockedURI));
        new Image().src = 'http://example.invalid/pixel.png';
        new Image().src = '/probe-of-the-recorder.png';
      });
      await new Promise((r) => setTimeout(r, 500));
      const errors = (await page.errors()).join('\n');
      assert.match(errors, /a console error/);
      assert.match(errors, /an uncaught error/);
      const requests = page.requests();
      assert.ok(requests.includes(`${b.base}/bench.html?frames=6&warmup=5&width=64&height=48`), requests.join(', '));
      assert.ok(requests.includes(`${b.base}/probe-of-the-recorder.png`), requests.join(', '));
      const refused = await page.eval(() => window.cspRefused);
      assert.ok(
        requests.includes('http://example.invalid/pixel.png') || refused.some((u) => u.startsWith('http://example.invalid')),
        `requests: ${requests.join(', ')}; refused by the CSP: ${refused.join(', ')}`,
      );
      await page.close();
    });

    test(`${N}: WebAssembly SIMD is there, and the page opens on the bundled clip and draws the tracked lane on it`, async () => {
      const page = await b.open(`${b.base}/`);
      // v128.const 0; i8x16.all_true: a module only a WebAssembly SIMD engine accepts.
      assert.equal(await page.eval(() => WebAssembly.validate(new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1,
        96, 0, 1, 127, 3, 2, 1, 0, 10, 24, 1, 22, 0, 253, 12, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 253, 99, 11]))), true,
      'WebAssembly SIMD validates');
      await running(page);
      assert.match(await text(page, '#version'), /^lanepf \d+\.\d+\.\d+/);
      assert.match(await text(page, '#status'), /Udacity project_video\.mp4.*640x360.*25 frames\/s/);
      assert.match(await text(page, '#status'), WEBCODECS_VP9[N] ? /decoded with WebCodecs/ : /by seeking a <video> element/);
      await framesAtLeast(page, 40);
      await page.click('#play');
      await page.waitFor(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.lastRgba?.length > 0);
      // (As one JSON string: see readCanvas.)
      const { estimate, rgba } = JSON.parse(await page.eval(() => JSON.stringify({
        estimate: window.lanepfDemo.lastEstimate, rgba: Array.from(window.lanepfDemo.lastRgba),
      })));
      assert.equal(estimate.valid, true);
      const frame = { width: 640, height: 360, data: rgba };
      // The browser decoded the VP9 clip into real pixels: blue sky at the top of the frame.
      const sky = 4 * (20 * 640 + 320);
      assert.ok(rgba[sky + 2] > rgba[sky] + 20, 'blue sky at the top of the frame');
      // The estimated ego-left boundary lies on painted line near the car: on most rows of the
      // lower image, brighter within 4 px of it than at the lane's centre.
      const left = estimate.boundaries.find((x) => x.role === 'ego-left').points;
      const right = estimate.boundaries.find((x) => x.role === 'ego-right').points;
      const rows = left.filter(([, y]) => y > 250 && y < 340);
      assert.ok(rows.length >= 5, `${rows.length} rows of the left boundary near the car`);
      let onPaint = 0;
      for (const [x, y] of rows) {
        const xr = right.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a))[0];
        if (peak(frame, x, y, 4) > lum(frame, (x + xr) / 2, y) + 30) onPaint++;
      }
      assert.ok(onPaint / rows.length > 0.8, `left boundary on paint on ${onPaint} of ${rows.length} rows`);
      // The canvas shows it: the ego-left colour, the particles, the top view and the plots.
      const canvas = await readCanvas(page);
      assert.equal(canvas.width, 640);
      assert.ok(countColour(canvas, [0xff, 0xd5, 0x4f]) > 200, 'ego-left overlay on the canvas');
      const cloud = await demo(page, 'lastHypotheses');
      assert.ok(cloud.length > 10 && cloud.every((h) => h.boundaries.length >= 1), 'particles drawn');
      assert.equal(await visible(page, '#top'), true, 'the top view is shown');
      const plots = await readCanvas(page, 'plots');
      assert.ok(countNear(plots, [0x4f, 0xc3, 0xf7], 40) > 300, 'the plots draw the estimate over time');
      assert.match(await text(page, '#timing'), /track \d+\.\d ms/);
      await page.screenshot(`test-results/${N.toLowerCase()}-clip.png`);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: the test road is drawn with markings where the ground truth says`, async () => {
      const page = await b.open(`${b.base}/?source=test-road&tracker=`);
      await running(page);
      await framesAtLeast(page, 3);
      // Freeze the stream, hide the overlay and draw one clean frame.
      await page.click('#play');
      await setChecked(page, '#show-truth', false);
      await idle(page);
      const before = await demo(page, 'frames');
      await page.click('#step');
      await page.waitFor((n) => window.lanepfDemo.frames > n, { arg: before });
      const truth = await demo(page, 'lastTruth');
      const img = await readCanvas(page);
      assert.equal(img.width, 640);
      assert.equal(img.height, 480);
      const left = truth.boundaries.find((x) => x.role === 'ego-left');
      const right = truth.boundaries.find((x) => x.role === 'ego-right');
      assert.ok(left && right && left.points.length >= 10, 'ground truth has both ego boundaries');
      // Solid left marking bright along its near polyline, dashed right one along part of it,
      // dark asphalt between them.
      const near = (pts) => pts.filter(([, y]) => y > 200);
      const hit = (pts) => near(pts).filter(([x, y]) => peak(img, x, y, 3) > 150).length / near(pts).length;
      assert.ok(hit(left.points) > 0.9, `solid marking found on ${hit(left.points)} of the left polyline`);
      const dashed = hit(right.points);
      assert.ok(dashed > 0.05 && dashed < 0.6, `dashed marking found on ${dashed} of the right polyline`);
      for (let k = 0; k < near(left.points).length; k += 3) {
        const [xl, y] = near(left.points)[k];
        const xr = right.points.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a))[0];
        assert.ok(lum(img, (xl + xr) / 2, y) < 140, `lane centre at row ${y} is asphalt`);
      }
      // With the overlay on, the ground truth is drawn in its colour (render.js's TRUTH_COLOUR).
      await setChecked(page, '#show-truth', true);
      const n2 = await demo(page, 'frames');
      await page.click('#step');
      await page.waitFor((n) => window.lanepfDemo.frames > n, { arg: n2 });
      const red = countColour(await readCanvas(page), [0xff, 0x17, 0x44]);
      assert.ok(red > 100, `ground truth overlay drawn (${red} px)`);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: every tracker can be chosen and tracks a synthetic scene within 0.3 m`, async () => {
      const page = await b.open(`${b.base}/?source=highway-straight&tracker=`);
      await running(page);
      const ids = (await page.eval(() => [...document.querySelectorAll('#tracker option')].map((o) => o.value)))
        .filter(Boolean);
      assert.deepEqual(ids, TRACKERS);
      const report = [];
      for (const id of ids) {
        await page.click('#play'); // pause while switching
        await page.click('#restart');
        await page.select('#tracker', id);
        // (The restart and the new tracker wait in the page's queue; until they have run, the
        // previous tracker's errors are still there.)
        await idle(page);
        await page.click('#play');
        await page.waitFor(() => window.lanepfDemo.offsetErrors.length >= 30, { timeout: 60_000 });
        const errs = await page.eval(() => window.lanepfDemo.offsetErrors.slice(20, 30));
        const valid = await page.eval(() => window.lanepfDemo.results.slice(20, 30).filter((r) => r.valid).length);
        const mean = errs.reduce((a, c) => a + c, 0) / errs.length;
        report.push(`${id} ${mean.toFixed(3)} (${valid} valid)`);
        assert.ok(mean < 0.3, `${id}: mean offset error ${mean.toFixed(3)} m over frames 20-29`);
        assert.ok(valid >= 8, `${id}: ${valid} of frames 20-29 valid`);
        // The status line names the time, says when the shown frame's estimate is not valid, and
        // gives its error.
        const [timing, shown] = await page.eval(() => [document.getElementById('timing').textContent,
          window.lanepfDemo.lastEstimate.valid]);
        assert.match(timing, shown ? /track \d+\.\d ms · offset error \d+ cm/ : /track \d+\.\d ms · not valid · offset error \d+ cm/);
      }
      console.log(`${N}, mean |offset error| frames 20-29: ${report.join(', ')}`);
      // Firefox rounds performance.now() to whole milliseconds unless the page is cross-origin
      // isolated (scripts/serve.mjs sends COOP/COEP); then the ms/frame readings are finer.
      const { isolated, ms } = await page.eval(() => ({
        isolated: window.crossOriginIsolated, ms: window.lanepfDemo.results.map((r) => r.ms),
      }));
      assert.equal(isolated, true, 'the demo page is cross-origin isolated');
      assert.ok(ms.filter((t) => !Number.isInteger(t)).length > ms.length / 2,
        `tracker times finer than whole milliseconds: ${ms.slice(0, 10).join(', ')}`);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: an uploaded video is read to its end (WebCodecs, else seeking); an undecodable file is explained`, async () => {
      const page = await b.open(`${b.base}/?source=highway-straight&tracker=adachi-mmpf`);
      await running(page);
      await page.setFiles('#file', [CLIP]);
      await page.waitFor(() => /Video “udacity-project-640x360\.webm”/.test(
        document.getElementById('status').textContent));
      if (WEBCODECS_VP9[N]) {
        // Frame count and rate from the container, frames from VideoDecoder.
        assert.match(await text(page, '#status'), /300 frames at 25 frames\/s, decoded with WebCodecs/);
      } else {
        // WebKitGTK here has a VideoDecoder that takes no VP9 (say so, so that a WebKitGTK that
        // does fails here): the page seeks, at the rate measured from requestVideoFrameCallback.
        assert.deepEqual(await page.eval(async () => [typeof VideoDecoder,
          (await VideoDecoder.isConfigSupported({ codec: 'vp09.00.10.08' })).supported]), ['function', false]);
        assert.match(await text(page, '#status'), new RegExp('read at 25 frames/s \\(measured\\), by seeking a <video> '
          + 'element \\(not WebCodecs: this browser\'s VideoDecoder does not decode vp09'));
      }
      await page.waitFor(() => window.lanepfDemo.frames > 30);
      const midway = await page.eval(() => document.getElementById('progress').value);
      assert.ok(midway > 0.05 && midway < 0.95, `progress ${midway} while running`);
      // Every frame is read: 12 s at 25 frames/s, none skipped or repeated.
      await page.waitFor(() => window.lanepfDemo.ended, { timeout: 120_000 });
      const names = await page.eval(() => window.lanepfDemo.results.map((r) => r.frame));
      assert.deepEqual(names, Array.from({ length: 300 }, (_, k) => `${k}`));
      assert.match(await text(page, '#status'), /End of .* 300 frames tracked/);

      await page.setFiles('#file', [writeFile('holiday.mp4', 'this is a text file, not a video\n')]);
      await pageState(page, 'error');
      assert.match(await text(page, '#status'), /Cannot open “holiday\.mp4”: .*Try an H\.264 MP4 or a VP9 WebM/);
      await page.setFiles('#file', [writeFile('broken.png', 'nope')]);
      await page.waitFor(() => /broken\.png/.test(document.getElementById('status').textContent));
      assert.match(await text(page, '#status'), /Cannot decode “broken\.png”/);
      // A browser with neither WebCodecs nor presented-frame callbacks: the page seeks, and the
      // rate it cannot measure is assumed, and says so.
      await page.eval(() => {
        delete window.VideoDecoder;
        delete HTMLVideoElement.prototype.requestVideoFrameCallback;
      });
      await page.setFiles('#file', [CLIP]);
      await page.waitFor(() => /Video “udacity-project-640x360\.webm”/.test(
        document.getElementById('status').textContent));
      assert.match(await text(page, '#status'), new RegExp('read at 30 frames/s \\(assumed: the browser did not '
        + 'report its frames\\), by seeking a <video> element \\(not WebCodecs: this browser has no WebCodecs VideoDecoder\\)'));
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: still images made in the page are tracked as a sequence with an imported camera`, async () => {
      const page = await b.open(`${b.base}/?source=test-road&tracker=lee-cpf`);
      await running(page);
      // Eight frames of a scene as PNG files (OffscreenCanvas.convertToBlob), and the scene's
      // camera as a camera.json.
      const { left: pngs, camera, truth } = await scenePngs(page, 'highway-straight', 3, 8);
      await openAdvanced(page);
      await page.setFiles('#camera-file', [writeFile('sim.camera.json', JSON.stringify(camera))]);
      await page.waitFor(() => /Camera “sim\.camera\.json”/.test(document.getElementById('status').textContent));
      const paths = pngs.map((b64, f) => writeFile(`frame-${f}.png`, Buffer.from(b64, 'base64')));
      // Names sort numerically whatever order they come in.
      await page.setFiles('#file', paths.reverse());
      await page.waitFor(() => window.lanepfDemo.ended);
      const results = await demo(page, 'results');
      assert.deepEqual(results.map((r) => r.frame), pngs.map((_, f) => `frame-${f}.png`));
      const last = results.at(-1);
      assert.ok(Math.abs(last.lateral_offset_m - truth) < 0.3,
        `offset ${last.lateral_offset_m} vs truth ${truth} after 8 images`);
      assert.match(await text(page, '#status'), /End of 8 images/);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: the webcam path runs on the browser's fake camera`, async () => {
      // (Firefox: media.navigator.streams.fake; WebKit: its mock capture devices. A moving test
      // picture, no permission prompt.)
      const page = await b.open(`${b.base}/?source=webcam&tracker=lee-cpf`);
      await running(page);
      await framesAtLeast(page, 5);
      assert.match(await text(page, '#status'), /^Webcam .*: 640x480/);
      const img = await readCanvas(page);
      const values = new Set();
      for (let y = 0; y < img.height; y += 40) for (let x = 0; x < img.width; x += 40) values.add(Math.round(lum(img, x, y)));
      assert.ok(values.size > 3, 'the fake camera\'s picture is drawn');
      assert.equal(await visible(page, '#progress'), false, 'a live source has no progress bar');
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: a refused camera permission is explained and the page keeps working`, async () => {
      const page = await b.open(`${b.base}/?source=test-road&tracker=`);
      await running(page);
      // What getUserMedia rejects with when a person clicks "Block" (the fake cameras here are
      // granted without asking). Replaced on the prototype: WebKit does not keep the JS object of
      // navigator.mediaDevices alive, so a property set on that object itself is gone when a
      // garbage collection drops it, and the page then opened the mock camera (6 of 25 runs).
      await page.eval(() => {
        MediaDevices.prototype.getUserMedia = () => Promise.reject(new DOMException('denied', 'NotAllowedError'));
      });
      await page.select('#source', 'webcam');
      await pageState(page, 'error');
      assert.match(await text(page, '#status'), /Camera permission was refused/);
      // The test road is still drawn.
      const n = await demo(page, 'frames');
      await page.click('#play');
      await page.waitFor((n) => window.lanepfDemo.frames > n + 2, { arg: n });
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: dragging the calibration helper's lines gives the scene camera's pose`, async () => {
      const page = await b.open(`${b.base}/?source=highway-straight&tracker=`);
      await running(page);
      await framesAtLeast(page, 2);
      await page.click('#play');
      await idle(page);
      const { truth, camera } = await page.eval(async () => {
        const m = await import('/pkg/sim/lanepf_sim.js');
        await m.default();
        const scene = new m.Scene('highway-straight', { width: 640, height: 480, seed: 1 });
        return { truth: window.lanepfDemo.lastTruth, camera: scene.camera() };
      });
      const fields = () => page.eval(() => Object.fromEntries(
        [...document.querySelectorAll('#camera-fields input')].map((i) => [i.name, Number(i.value)]),
      ));
      assert.equal((await fields()).pitch_deg, camera.pitch_deg);
      await page.click('#calibration summary');
      await setChecked(page, '#vp-helper', true);
      const at = (role, y) => {
        const pts = truth.boundaries.find((x) => x.role === role).points;
        return pts.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a));
      };
      const starts = [[0.3 * 640, 0.95 * 480], [0.46 * 640, 0.65 * 480], [0.7 * 640, 0.95 * 480], [0.54 * 640, 0.65 * 480]];
      const targets = [at('ego-left', 440), at('ego-left', 330), at('ego-right', 440), at('ego-right', 330)];
      for (let k = 0; k < 4; k++) {
        // (Measured each time: the status line above the canvas may change its height.)
        const box = await page.eval(() => {
          const v = document.getElementById('view');
          v.scrollIntoView({ block: 'center', inline: 'center' });
          const r = v.getBoundingClientRect();
          return { x: r.x, y: r.y, width: r.width, height: r.height };
        });
        const sx = box.width / 640;
        const sy = box.height / 480;
        await page.drag([box.x + starts[k][0] * sx, box.y + starts[k][1] * sy],
          [box.x + targets[k][0] * sx, box.y + targets[k][1] * sy], 4);
        await idle(page);
      }
      const got = await fields();
      // The lane heads psi left of the car: its vanishing point is psi to the left, so the
      // helper reads a yaw of camera yaw - psi (there is no car sway it could tell apart).
      const psiDeg = (truth.heading_rad * 180) / Math.PI;
      // Danescu's alpha is the camera's pitch over the road, body pitch included.
      const pitchTruth = (truth.state['danescu.alpha'] * 180) / Math.PI;
      console.log(`${N} helper: pitch ${got.pitch_deg} (truth ${pitchTruth}), yaw ${got.yaw_deg} `
        + `(${camera.yaw_deg - psiDeg}), height ${got.height_m} (${camera.height_m})`);
      assert.ok(Math.abs(got.pitch_deg - pitchTruth) < 0.5, `pitch ${got.pitch_deg} vs ${pitchTruth}`);
      assert.ok(Math.abs(got.yaw_deg - (camera.yaw_deg - psiDeg)) < 0.5, `yaw ${got.yaw_deg}`);
      assert.ok(Math.abs(got.height_m / camera.height_m - 1) < 0.1, `height ${got.height_m}`);
      assert.match(await text(page, '#status'), /Camera applied: pitch/);
      assert.match(await text(page, '#vp-readout'), /vanishing point \(\d+, \d+\)/);
      // Remembered for this source (localStorage): a reload uses it.
      await page.reload();
      await running(page);
      assert.match(await text(page, '#status'), /as you calibrated it for this source/);
      assert.equal((await fields()).pitch_deg, +got.pitch_deg.toFixed(4));
      // (Forgotten again, so the later tests see the scene's own camera.)
      await page.eval(() => localStorage.clear());
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: bench.html times every tracker in a worker, finer than whole milliseconds`, async () => {
      const page = await b.open('about:blank');
      await page.goto(`${b.base}/bench.html?frames=8&width=320&height=240`);
      await page.waitFor(() => window.lanepfBench?.done, { timeout: 110_000 });
      const bench = await page.eval(() => window.lanepfBench);
      assert.equal(bench.error, undefined, bench.error);
      assert.deepEqual(bench.rows.map((r) => r.tracker), TRACKERS);
      for (const r of bench.rows) {
        assert.ok(Number.isFinite(r.median_ms) && r.median_ms > 0, `${r.tracker}: median ${r.median_ms}`);
        assert.ok(Number.isFinite(r.p95_ms) && r.p95_ms >= r.median_ms, `${r.tracker}: p95 ${r.p95_ms}`);
        assert.equal(r.frames, 3, `${r.tracker}: 8 frames, the first 5 untimed`);
        assert.deepEqual([r.width, r.height], [320, 240]);
      }
      // The table and the JSON on the page say the same.
      assert.equal(await page.eval(() => document.querySelectorAll('#table tbody tr').length), TRACKERS.length);
      assert.deepEqual(JSON.parse(await text(page, '#result')).rows, bench.rows);
      // Sub-millisecond trackers at this size read as 0 or 1 ms on a whole-millisecond clock.
      assert.ok(bench.rows.some((r) => !Number.isInteger(r.median_ms)),
        `medians ${bench.rows.map((r) => r.median_ms).join(', ')} are not all whole milliseconds`);
      assert.deepEqual(await page.errors(), []);
      const requests = page.requests();
      const foreign = requests.filter((u) => !u.startsWith(b.base) && !u.startsWith('data:') && u !== 'about:blank');
      assert.ok(requests.some((u) => u.endsWith('/pkg/web/lanepf_bg.wasm')), 'requests are seen');
      assert.ok(requests.some((u) => u.endsWith('/pkg/sim/lanepf_sim_bg.wasm')), 'the simulator\'s module is loaded');
      assert.deepEqual(foreign, [], 'no requests beyond the page\'s own files');
      await page.close();
    });

    test(`${N}: bench.html reports bad parameters as an error`, async () => {
      const page = await b.open(`${b.base}/bench.html?frames=3&warmup=5`);
      await page.waitFor(() => window.lanepfBench?.done);
      const bench = await page.eval(() => window.lanepfBench);
      assert.match(bench.error, /frames=3 must exceed warmup=5/);
      assert.equal(await page.eval(() => document.body.dataset.state), 'error');
      await page.close();
      const unknown = await b.open(`${b.base}/bench.html?preset=fast`);
      await unknown.waitFor(() => window.lanepfBench?.done);
      assert.match((await unknown.eval(() => window.lanepfBench)).error, /preset=fast: use one of paper, real-roads/);
      await unknown.close();
    });

    test(`${N}: bench.html times a tracker with the real-roads preset's options`, async () => {
      const page = await b.open(`${b.base}/bench.html?frames=7&width=320&height=240&trackers=lee-cpf&preset=real-roads`);
      await page.waitFor(() => window.lanepfBench?.done, { timeout: 110_000 });
      const bench = await page.eval(() => window.lanepfBench);
      assert.equal(bench.error, undefined, bench.error);
      assert.deepEqual(bench.rows.map((r) => [r.tracker, r.preset]), [['lee-cpf', 'real-roads']]);
      // The tracker ran with the preset's options: lee-cpf's re-lock proposal is on in it.
      assert.equal(bench.rows[0].options.relock_share, 0.05);
      assert.ok(Number.isFinite(bench.rows[0].median_ms) && bench.rows[0].median_ms > 0);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: the keyboard plays, pauses, steps a frame and steps a stage`, async () => {
      const page = await b.open(`${b.base}/?source=highway-straight&tracker=lee-cpf`);
      await running(page);
      await page.clickAt(5, 5);
      await page.press(' ');
      assert.equal(await text(page, '#play'), 'Play', 'space pauses');
      await idle(page);
      const n = await page.eval(() => window.lanepfDemo.results.length);
      await page.press('.');
      await page.waitFor((n) => window.lanepfDemo.results.length === n + 1, { arg: n });
      await page.press(',');
      await page.waitFor(() => !/start of a frame/.test(document.getElementById('next-stage').textContent));
      await page.press(' ');
      assert.equal(await text(page, '#play'), 'Pause', 'space plays again');
      // Playing finishes the half-stepped frame first, then goes on.
      await page.waitFor((n) => window.lanepfDemo.results.length >= n + 4, { arg: n });
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: the per-step mode runs one stage of the filter per click and redraws the cloud`, async () => {
      const page = await b.open(`${b.base}/?source=highway-curve&tracker=lee-cpf`);
      await running(page);
      await page.waitFor(() => window.lanepfDemo.results.length >= 3);
      await page.click('#play');
      await idle(page);
      assert.equal(await enabled(page, '#step-stage'), true);
      const names = await page.eval(async () => {
        const [m, sim] = await Promise.all([import('/pkg/web/lanepf.js'), import('/pkg/sim/lanepf_sim.js')]);
        await Promise.all([m.default(), sim.default()]);
        const scene = new sim.Scene('highway-curve', { width: 320, height: 240, seed: 1 });
        return new m.Tracker('lee-cpf', { camera: scene.camera() }).stepNames();
      });
      assert.ok(names.length >= 4, names.join());
      const frames = await page.eval(() => window.lanepfDemo.results.length);
      assert.match(await text(page, '#next-stage'), /next: start of a frame/);
      // The first click starts the frame (its cues); each next click runs one named step.
      await page.click('#step-stage');
      await page.waitFor(() => /next: /.test(document.getElementById('next-stage').textContent)
        && !/start of a frame/.test(document.getElementById('next-stage').textContent));
      const clouds = [];
      for (let k = 0; k < names.length; k++) {
        assert.equal(await text(page, '#next-stage'), `next: ${names[k]}`);
        const drawn = await demo(page, 'frames');
        await page.click('#step-stage');
        await page.waitFor((n) => window.lanepfDemo.frames > n, { arg: drawn });
        assert.match(await text(page, '#status'), new RegExp(`ran “${names[k].replace(/[[\]().*+?]/g, '\\$&')}”`));
        clouds.push(await page.eval(() => JSON.stringify(window.lanepfDemo.lastHypotheses)));
        const done = await page.eval(() => window.lanepfDemo.results.length);
        // The estimate (one more result) comes with the last step, not before.
        assert.equal(done, k === names.length - 1 ? frames + 1 : frames, `after step ${k}`);
      }
      assert.ok(new Set(clouds).size >= 3, 'the cloud moves between steps');
      assert.match(await text(page, '#next-stage'), /next: start of a frame/);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: two trackers run side by side on the same frames`, async () => {
      const page = await b.open(`${b.base}/?source=highway-straight&tracker=lee-cpf`);
      await running(page);
      assert.equal(await visible(page, '#view2'), false, 'no second view until asked');
      // (Both trackers are rebuilt mid-scene: each must find the lane from a cold start.)
      await page.select('#compare', 'adachi-mmpf');
      await page.waitFor(() => window.lanepfDemo.lastCompare && window.lanepfDemo.results.length >= 20);
      await page.click('#play');
      await idle(page);
      const { main, other, truth } = await page.eval(() => ({
        main: window.lanepfDemo.lastEstimate, other: window.lanepfDemo.lastCompare, truth: window.lanepfDemo.lastTruth,
      }));
      assert.equal(other.trackerId, 'adachi-mmpf');
      assert.equal(main.state['lee.psi'] !== undefined, true, 'the main view is still lee-cpf');
      assert.ok(other.estimate.state['adachi.q'] !== undefined, 'the second view is adachi-mmpf');
      for (const e of [main, other.estimate]) {
        assert.ok(Math.abs(e.lateral_offset_m - truth.lateral_offset_m) < 0.3,
          `offset ${e.lateral_offset_m} vs truth ${truth.lateral_offset_m}`);
      }
      assert.equal(await visible(page, '#view2'), true);
      assert.match(await text(page, '#compare-caption'), /^adachi-mmpf · track \d+\.\d ms · offset error \d+ cm/);
      // The second canvas shows the frame with the ego-left colour drawn on it.
      const yellow = countColour(await readCanvas(page, 'view2'), [0xff, 0xd5, 0x4f]);
      assert.ok(yellow > 100, `ego-left drawn on the second view (${yellow} px)`);
      await page.select('#compare', '');
      await page.click('#step');
      await page.waitFor(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.frames >= 1);
      assert.equal(await visible(page, '#view2'), false);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: a run exports as JSON lines in the track format and as CSV`, async () => {
      const page = await b.open(`${b.base}/?source=highway-straight&tracker=adachi-mmpf`);
      await running(page);
      await captureDownloads(page);
      await page.waitFor(() => window.lanepfDemo.results.length >= 6);
      await page.click('#play');
      await idle(page); // the frame in flight
      const n = await page.eval(() => window.lanepfDemo.results.length);
      const saved = async (k) => page.waitFor((k) => window.__downloads[k]?.text !== null
        && window.__downloads[k], { arg: k });
      await page.click('#export-jsonl');
      const jsonl = await saved(0);
      assert.equal(jsonl.name, 'lanepf-adachi-mmpf-highway-straight.jsonl');
      assert.equal(jsonl.type, 'application/x-ndjson');
      const lines = jsonl.text.split('\n');
      assert.equal(lines.pop(), '', 'newline-terminated');
      assert.equal(lines.length, n);
      lines.forEach((line, k) => {
        const r = JSON.parse(line);
        assert.equal(r.frame, `${k}`);
        assert.equal(typeof r.valid, 'boolean');
        for (const key of ['lateral_offset_m', 'heading_rad', 'curvature_per_m', 'lane_width_m', 'ms']) {
          assert.ok(Number.isFinite(r[key]), `${key} in line ${k}`);
        }
        assert.ok(r.boundaries.some((x) => x.role === 'ego-left' && x.points.length > 5));
        assert.ok(Number.isFinite(r.state['adachi.q']));
      });
      await page.click('#export-csv');
      const csv = await saved(1);
      assert.equal(csv.name, 'lanepf-adachi-mmpf-highway-straight.csv');
      const rows = csv.text.trim().split('\n');
      assert.equal(rows[0], 'frame,valid,lateral_offset_m,heading_rad,curvature_per_m,lane_width_m,ms');
      assert.equal(rows.length, n + 1);
      assert.equal(Number(rows[1].split(',')[2]), JSON.parse(lines[0]).lateral_offset_m);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: the teaching panel explains the tracker, its sliders rebuild it, and the seed makes runs repeat`, async () => {
      const page = await b.open(`${b.base}/?source=highway-straight&tracker=adachi-mmpf`);
      await running(page);
      assert.match(await text(page, '#teach-title'), /Adachi/);
      assert.match(await text(page, '#teach-text'), /Table 1/);
      const defaults = await page.eval(() => Object.fromEntries([...document.querySelectorAll('#params input')]
        .map((i) => [i.name, i.type === 'checkbox' ? i.checked : Number(i.value)])));
      assert.equal(defaults.particles, 500);
      assert.equal(defaults.sigma_q_m, 0.08);
      // Fewer particles: the tracker is rebuilt, and the drawn cloud is all of its 60 particles.
      await page.click('#play');
      await idle(page);
      await setValue(page, '#params input[name="particles"]', '60');
      await page.waitFor(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.frames === 0);
      await page.click('#step');
      await page.waitFor(() => window.lanepfDemo.frames === 1);
      assert.equal(await page.eval(() => window.lanepfDemo.lastHypotheses.length), 60);
      // The same seed from the same frame gives the same run; another seed another one.
      const run = async (seed) => {
        await setValue(page, '#seed', `${seed}`);
        await page.click('#restart');
        await page.waitFor(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.results.length === 0);
        for (let k = 0; k < 5; k++) {
          await page.click('#step');
          await page.waitFor((k) => window.lanepfDemo.results.length === k + 1, { arg: k });
        }
        return page.eval(() => window.lanepfDemo.results.map((r) => r.lateral_offset_m));
      };
      const a = await run(7);
      const c7 = await run(7);
      const c8 = await run(8);
      assert.deepEqual(a, c7);
      assert.notDeepEqual(a, c8);
      // Back to the paper's defaults.
      await page.click('#params-reset');
      await page.waitFor(() => document.querySelector('#params input[name="particles"]').value === '500');
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: the panel's beyond-the-paper box adds the lanes beside the ego lane`, async () => {
      // multi-lane: four lanes, the car in the second, so a lane on each side.
      const page = await b.open(`${b.base}/?source=multi-lane&tracker=lee-cpf`);
      await running(page);
      await page.click('#play');
      await idle(page);
      const roles = async () => {
        await page.click('#restart');
        await page.waitFor(() => window.lanepfDemo.pending === 0 && window.lanepfDemo.results.length === 0);
        for (let k = 0; k < 5; k++) {
          await page.click('#step');
          await page.waitFor((k) => window.lanepfDemo.results.length === k + 1, { arg: k });
        }
        return page.eval(() => window.lanepfDemo.lastEstimate.boundaries.map((x) => x.role).sort());
      };
      // The paper's lee-cpf: the ego lane only.
      assert.equal(await page.eval(() => document.querySelector('#params input[name="adjacent_lanes"]').checked), false);
      assert.deepEqual(await roles(), ['ego-left', 'ego-right']);
      await page.click('#params input[name="adjacent_lanes"]');
      await idle(page);
      assert.deepEqual(await roles(), ['ego-left', 'ego-right', 'left-adjacent', 'right-adjacent']);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: real footage starts from the real-roads options, the simulator from the paper's, and both buttons switch`, async () => {
      const page = await b.open(`${b.base}/?source=clip&tracker=lee-cpf`);
      await running(page);
      const values = () => page.eval(() => Object.fromEntries([...document.querySelectorAll('#params input')]
        .map((i) => [i.name, i.type === 'checkbox' ? i.checked : Number(i.value)])));
      // The bundled clip: our options beyond the paper, named on the panel.
      let v = await values();
      assert.equal(v.relock_share, 0.05);
      assert.equal(v.curvature_prior_sd, 0.004);
      assert.equal(v.adjacent_lanes, true);
      assert.equal(v.valid_support_frames, 5);
      assert.match(await text(page, '#params-preset'), /real roads \(ours.*relock_share.*\)/);
      // Back to the paper's filter, and to real roads again, with the buttons.
      await page.click('#params-reset');
      await page.waitFor(() => document.querySelector('#params input[name="relock_share"]').value === '0');
      v = await values();
      assert.equal(v.adjacent_lanes, false);
      assert.equal(v.curvature_prior_sd, 0);
      assert.equal(v.valid_support_frames, 1);
      assert.match(await text(page, '#params-preset'), /the paper’s filter/);
      await page.click('#params-real-roads');
      await page.waitFor(() => document.querySelector('#params input[name="relock_share"]').value === '0.05');
      // Another tracker keeps the preset: danescu-mono's real-roads options.
      await page.select('#tracker', 'danescu-mono');
      await page.waitFor(() => document.querySelector('#params input[name="relock_share"]')?.value === '0.1');
      assert.equal(await page.eval(() => document.querySelector('#params input[name="start_iterations"]').value), '10');
      assert.equal(await page.eval(() => document.querySelector('#params input[name="valid_support_frames"]').value), '5');
      // A comparison tracker runs the same preset: adachi-mmpf's real-roads options.
      await page.select('#compare', 'adachi-mmpf');
      await page.waitFor(() => window.lanepfDemo.compareOptions?.relock_share === 0.05);
      // A simulator scene starts from the paper's, the comparison tracker too.
      await page.select('#source', 'highway-straight');
      await page.waitFor(() => document.querySelector('#params input[name="relock_share"]')?.value === '0');
      await page.waitFor(() => Object.keys(window.lanepfDemo.compareOptions ?? { x: 1 }).length === 0);
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });

    test(`${N}: danescu-stereo tracks left/right image pairs and side-by-side images`, async () => {
      const page = await b.open(`${b.base}/?source=test-road&tracker=danescu-stereo`);
      // The test road's camera is not a stereo rig: the page says so and keeps going.
      await pageState(page, 'error');
      assert.match(await text(page, '#status'), /needs `baseline_m`.*import a camera file with baseline_m/);
      // Sixteen stereo frames of a simulator scene, as PNGs, and its camera (with the baseline).
      // (danescu-stereo starts 0.5 m off on this scene and needs about ten frames to settle.)
      const { left, right, sbs, camera, truth } = await scenePngs(page, 'highway-straight', 2, 16, true);
      assert.ok(camera.baseline_m > 0, 'the scene camera is a stereo rig');
      const png = (name, b64) => writeFile(name, Buffer.from(b64, 'base64'));
      await openAdvanced(page);
      await page.setFiles('#camera-file', [writeFile('rig.camera.json', JSON.stringify(camera))]);
      await page.waitFor(() => /Camera “rig\.camera\.json”/.test(document.getElementById('status').textContent));
      // (The error paused the page; opening a source keeps it paused until Play.)
      const play = async () => {
        await idle(page);
        if ((await text(page, '#play')) === 'Play') await page.click('#play');
      };
      // Mono images to a stereo tracker: the error says what to do in this page.
      await page.setFiles('#file', [png('only-left.png', left[0])]);
      await play();
      await pageState(page, 'error');
      assert.match(await text(page, '#status'), /needs the right image.*tick Stereo/);

      await setChecked(page, '#stereo', true);
      for (const [what, paths, label] of [
        ['pairs', left.flatMap((l, f) => [png(`f${f}_left.png`, l), png(`f${f}_right.png`, right[f])]), /16 stereo pairs/],
        ['side by side', sbs.map((s, f) => png(`sbs${f}.png`, s)), /16 side-by-side stereo images/],
      ]) {
        await page.setFiles('#file', paths);
        await play();
        await page.waitFor(() => window.lanepfDemo.ended, { timeout: 60_000 });
        assert.match(await text(page, '#status'), label, what);
        const results = await demo(page, 'results');
        assert.equal(results.length, 16, what);
        const last = results.at(-1);
        assert.ok(Number.isFinite(last.state['danescu.pitch_detected']), `${what}: the stereo cue ran`);
        assert.ok(Math.abs(last.lateral_offset_m - truth) < 0.3, `${what}: offset ${last.lateral_offset_m} vs ${truth}`);
      }
      assert.deepEqual(await page.errors(), []);
      await page.close();
    });
  });
}
