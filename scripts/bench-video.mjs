// Times reading a video frame by frame in headless Chromium, two ways: decoded with WebCodecs
// (www/webcodecs-source.js) and by seeking a <video> element (www/media-source.js), each frame
// drawn to the tracker's canvas and read back as RGBA, as the demo does; no tracker. With a
// tracker id, also the demo's whole run of the uploaded file to its end, both ways.
//   node scripts/bench-video.mjs [FILE (default or "": the bundled clip)] [TRACKER]
import { fileURLToPath } from 'node:url';
import { start, open } from '../tests/e2e/browser.mjs';

const file = process.argv[2] || fileURLToPath(new URL('../www/clips/udacity-project-640x360.webm', import.meta.url));
const tracker = process.argv[3] || '';
const env = await start();

/** Reads every frame of the chosen file with `kind`; returns { frames, ms, label }. */
async function readAll(kind) {
  const { page } = await open(env.browser, `${env.base}/?source=test-road&tracker=`);
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 60000 });
  await page.evaluate(() => {
    const input = Object.assign(document.createElement('input'), { type: 'file', id: 'bench-file' });
    document.body.append(input);
  });
  await page.setInputFiles('#bench-file', file);
  const out = await page.evaluate(async (kind) => {
    const f = document.getElementById('bench-file').files[0];
    const { VideoSource } = await import('/media-source.js');
    const { WebCodecsVideoSource } = await import('/webcodecs-source.js');
    const t0 = performance.now();
    const source = kind === 'webcodecs' ? new WebCodecsVideoSource({ blob: f, name: f.name })
      : new VideoSource({ file: f, name: f.name });
    await source.open();
    let frames = 0;
    while (await source.next()) frames++;
    const ms = performance.now() - t0;
    source.close();
    return { frames, ms, label: source.label };
  }, kind);
  await page.close();
  return out;
}

/** The demo's run of the uploaded file with `tracker`, from upload to the end. */
async function demoRun(kind) {
  const page = await env.browser.newPage();
  if (kind === 'seeking') await page.addInitScript(() => { delete window.VideoDecoder; });
  await page.goto(`${env.base}/?source=test-road&tracker=${tracker}`);
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 60000 });
  const t0 = Date.now();
  await page.setInputFiles('#file', file);
  await page.waitForFunction(() => window.lanepfDemo.ended, null, { timeout: 3600e3, polling: 500 });
  const ms = Date.now() - t0;
  const frames = await page.evaluate(() => window.lanepfDemo.results.length);
  await page.close();
  return { frames, ms };
}

console.log(`${file}`);
for (const kind of ['webcodecs', 'seeking']) {
  const r = await readAll(kind);
  console.log(`read, ${kind}: ${r.frames} frames in ${(r.ms / 1000).toFixed(2)} s, `
    + `${(r.ms / r.frames).toFixed(2)} ms/frame, ${((1000 * r.frames) / r.ms).toFixed(1)} frames/s (${r.label})`);
}
if (tracker) {
  for (const kind of ['webcodecs', 'seeking']) {
    const r = await demoRun(kind);
    console.log(`demo with ${tracker}, ${kind}: ${r.frames} frames in ${(r.ms / 1000).toFixed(2)} s, `
      + `${(r.ms / r.frames).toFixed(2)} ms/frame`);
  }
}
await env.close();
