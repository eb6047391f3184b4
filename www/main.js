// The demo page: wires the worker, a frame source, the renderer and the controls together.
// One frame at a time: ask the source for a frame, draw it, draw the overlays, repeat.
import { WorkerClient } from './worker-client.js';
import { SceneSource, TestRoadSource } from './source.js';
import { Controls } from './controls.js';
import { drawFrame, drawBoundaries, drawLayer } from './render.js';

const controls = new Controls();
const ctx = document.getElementById('view').getContext('2d');
const cues = document.getElementById('cues').getContext('2d');
const client = new WorkerClient();
// Read by the end-to-end tests and handy in the console.
const demo = (window.lanepfDemo = { frames: 0, lastTruth: null, lastFrame: null });

function draw(frame) {
  drawFrame(ctx, frame.rgba, frame.width, frame.height);
  if (controls.showTruth.checked && frame.truth) {
    drawBoundaries(ctx, frame.truth.boundaries, { dashed: true, width: 2 });
  }
  if (frame.estimate) drawBoundaries(ctx, frame.estimate.boundaries, { width: 4 });
  // The tracker's first layer (its main cue: Adachi's votes, Lee's map, Liu's pixels).
  const layer = frame.layers?.[0];
  document.getElementById('cues-figure').hidden = !layer;
  if (layer) {
    drawLayer(cues, layer);
    document.getElementById('cues-caption').textContent = layer.name;
  }
  demo.lastLayer = layer ?? null;
  demo.lastEstimate = frame.estimate;
  demo.frames += 1;
  demo.lastTruth = frame.truth;
  demo.lastFrame = { index: frame.index, width: frame.width, height: frame.height };
  let text = `frame ${frame.index} · render ${frame.ms.toFixed(1)} ms`;
  if (frame.estimate) {
    text += ` · track ${frame.trackMs.toFixed(1)} ms`;
    if (frame.truth) {
      const err = Math.abs(frame.estimate.lateral_offset_m - frame.truth.lateral_offset_m);
      text += ` · offset error ${(100 * err).toFixed(0)} cm`;
    }
  }
  controls.timing.textContent = text;
}

async function main() {
  const { version, trackers, scenarios } = await client.request('hello');
  controls.version.textContent = `lanepf ${version}`;
  controls.setTrackers(trackers);
  controls.setScenarios(scenarios);
  let source = null;
  // The tracker is rebuilt for each source (it needs the source's camera).
  const openTracker = (id) => client.request('openTracker', { trackerId: id, camera: source.camera });
  const open = async (value) => {
    const scene = scenarios.find((s) => s.name === value);
    const next = scene ? new SceneSource(client, scene.name, scene.description) : new TestRoadSource(client);
    await next.open();
    source = next;
    controls.say(source.label);
    await openTracker(controls.tracker.value);
  };
  await open(controls.source.value);
  controls.onSource = (value) => open(value).catch((err) => controls.say(err.message, true));
  controls.onTracker = (id) => openTracker(id).catch((err) => controls.say(err.message, true));
  document.body.dataset.state = 'running';

  let busy = false;
  const advance = async () => {
    if (busy) return;
    busy = true;
    try {
      draw(await source.next({ layers: controls.showCues.checked }));
    } catch (err) {
      document.body.dataset.state = 'error';
      controls.say(err.message, true);
      controls.setPaused(true);
    } finally {
      busy = false;
    }
  };
  controls.onStep = advance;
  const loop = async () => {
    if (!controls.paused) await advance();
    requestAnimationFrame(loop);
  };
  requestAnimationFrame(loop);
}

main().catch((err) => {
  document.body.dataset.state = 'error';
  controls.say(`Could not start: ${err.message}`, true);
});
