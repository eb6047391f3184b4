// End-to-end: the camera panel. Dragging the helper's two lines onto a straight road's lane
// markings gives the scene camera's pitch, yaw and height; the camera is remembered for the
// source across a reload.
import test from 'node:test';
import assert from 'node:assert/strict';
import { start, open } from './browser.mjs';

const env = await start();
test.after(() => env.close());

test('pitch, yaw and height from two dragged lane lines, remembered per source', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=`);
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 30000 });
  await page.waitForFunction(() => window.lanepfDemo.frames >= 2);
  await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  const { truth, camera } = await page.evaluate(async () => {
    const m = await import('/pkg/web/lanepf.js');
    await m.default();
    const scene = new m.Scene('highway-straight', { width: 640, height: 480, seed: 1 });
    return { truth: window.lanepfDemo.lastTruth, camera: scene.camera() };
  });
  const fields = () => page.evaluate(() => Object.fromEntries(
    [...document.querySelectorAll('#camera-fields input')].map((i) => [i.name, Number(i.value)]),
  ));
  assert.equal((await fields()).pitch_deg, camera.pitch_deg);

  await page.click('#calibration summary');
  await page.check('#vp-helper');
  // Start lines are generic; drag each handle onto the truth's ego boundaries at two rows.
  const at = (role, y) => {
    const pts = truth.boundaries.find((b) => b.role === role).points;
    return pts.reduce((a, p) => (Math.abs(p[1] - y) < Math.abs(a[1] - y) ? p : a));
  };
  const starts = [[0.3 * 640, 0.95 * 480], [0.46 * 640, 0.65 * 480], [0.7 * 640, 0.95 * 480], [0.54 * 640, 0.65 * 480]];
  const targets = [at('ego-left', 440), at('ego-left', 330), at('ego-right', 440), at('ego-right', 330)];
  for (let k = 0; k < 4; k++) {
    // (Measured each time: the status line above the canvas may change its height.)
    await page.locator('#view').scrollIntoViewIfNeeded();
    const box = await page.locator('#view').boundingBox();
    const sx = box.width / 640;
    const sy = box.height / 480;
    await page.mouse.move(box.x + starts[k][0] * sx, box.y + starts[k][1] * sy);
    await page.mouse.down();
    await page.mouse.move(box.x + targets[k][0] * sx, box.y + targets[k][1] * sy, { steps: 4 });
    await page.mouse.up();
    await page.waitForFunction(() => window.lanepfDemo.pending === 0);
  }
  const got = await fields();
  // The lane heads psi left of the car: its vanishing point is psi to the left, so the
  // helper reads a yaw of camera yaw - psi (there is no car sway it could tell apart).
  const psiDeg = (truth.heading_rad * 180) / Math.PI;
  // Danescu's alpha is the camera's pitch over the road, body pitch included.
  const pitchTruth = (truth.state['danescu.alpha'] * 180) / Math.PI;
  console.log(`helper: pitch ${got.pitch_deg} (truth ${pitchTruth}), yaw ${got.yaw_deg} `
    + `(${camera.yaw_deg - psiDeg}), height ${got.height_m} (${camera.height_m})`);
  assert.ok(Math.abs(got.pitch_deg - pitchTruth) < 0.5, `pitch ${got.pitch_deg} vs ${pitchTruth}`);
  assert.ok(Math.abs(got.yaw_deg - (camera.yaw_deg - psiDeg)) < 0.5, `yaw ${got.yaw_deg}`);
  assert.ok(Math.abs(got.height_m / camera.height_m - 1) < 0.1, `height ${got.height_m}`);
  assert.match(await page.textContent('#status'), /Camera applied: pitch/);
  assert.match(await page.textContent('#vp-readout'), /vanishing point \(\d+, \d+\)/);

  // Remembered for this source: a reload uses it.
  await page.reload();
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 30000 });
  assert.match(await page.textContent('#status'), /as you calibrated it for this source/);
  assert.equal((await fields()).pitch_deg, +got.pitch_deg.toFixed(4));
  assert.deepEqual(errors, []);
  await page.close();
});

test('bad camera fields give a message, are not remembered, and a good camera brings the tracker back', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await page.waitForFunction(() => document.body.dataset.state === 'running', null, { timeout: 30000 });
  await page.click('#calibration summary');
  await page.fill('#camera-fields input[name="fx"]', '');
  await page.click('#camera-apply');
  assert.match(await page.textContent('#vp-readout'), /Camera fx: “” is not a number/);
  // A number the camera model refuses: the tracker's Error, shown in the status line.
  await page.fill('#camera-fields input[name="fx"]', '-5');
  await page.click('#camera-apply');
  await page.waitForFunction(() => document.body.dataset.state === 'error');
  assert.match(await page.textContent('#status'), /fx/);
  assert.equal(await page.evaluate(() => localStorage.getItem('lanepf.camera.highway-straight')), null,
    'a camera the tracker refused is not remembered');
  // Back to a good camera: frames flow again.
  await page.fill('#camera-fields input[name="fx"]', '309.4362');
  await page.click('#camera-apply');
  await page.waitForFunction(() => /Camera applied/.test(document.getElementById('status').textContent));
  if ((await page.textContent('#play')) === 'Play') await page.click('#play');
  await page.waitForFunction(() => window.lanepfDemo.results.length > 3);
  assert.deepEqual(errors, []);
  await page.close();
});
