// End-to-end in Chromium: the camera panel refuses bad fields. (Dragging the helper's two lines
// onto a straight road's lane markings, in every browser: cross-browser.test.mjs.)
import test from 'node:test';
import assert from 'node:assert/strict';
import { start, open, running } from './browser.mjs';

const env = await start();
test.after(() => env.close());

test('bad camera fields give a message, are not remembered, and a good camera brings the tracker back', async () => {
  const { page, errors } = await open(env.browser, `${env.base}/?source=highway-straight&tracker=lee-cpf`);
  await running(page);
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
