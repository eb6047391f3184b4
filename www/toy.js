// @ts-check
// The first lesson (toy.html): a 1-D particle filter (toy-filter.js) with the demo's step
// controls: play, a whole step, one stage, restart, and the same keys (space, `.`, `,`). Each
// stage is told in the status line ("resample: skipped: ESS 150 > 100"); the weight histogram
// and the ESS plot follow every stage; a resampling that happens is animated.
import { byId, context2d } from './dom.js';
import { ToyFilter, DEFAULTS } from './toy-filter.js';
import { drawView, drawHistogram, drawEss } from './toy-render.js';

/** How long the resampling animation lasts, and the pause between stages when playing (ms). */
const ANIMATION_MS = 700;
const PLAY_STAGE_MS = 350;

/** @param {string} id */
const $ = (id) => byId(id, HTMLElement);
const view = context2d('toy-view');
const hist = context2d('toy-hist');
const essCtx = context2d('toy-ess');
const form = byId('toy-params', HTMLFormElement);

let filter = new ToyFilter(readOptions());
/** ESS after each weighing, and whether the step resampled (the ESS plot). */
/** @type {{ step: number, ess: number, resampled: boolean }[]} */
let history = [];
/** The resampling being animated (null: none). */
/** @type {{ before: number[], weightsBefore: number[], parents: number[] } | null} */
let animation = null;
let playing = false;
/** @type {ReturnType<typeof setTimeout> | undefined} */
let timer;
// Read by the end-to-end test and handy in the console (`last`: what the last stage did).
/** @type {{ filter: ToyFilter, history: typeof history, animating: boolean, animationFrames: number, stages: number, last?: object | null }} */
const lesson = { filter, history, animating: false, animationFrames: 0, stages: 0 };
window.toyLesson = lesson;

function readOptions() {
  /** @type {Record<string, number>} */
  const o = { ...DEFAULTS };
  for (const input of form.querySelectorAll('input')) o[input.name] = Number(input.value);
  return o;
}

function drawAll() {
  if (!animation) drawView(view, filter);
  drawHistogram(hist, filter);
  drawEss(essCtx, history, filter.x.length, filter.options.essThreshold);
  $('toy-next').textContent = `next: ${filter.nextStage}`;
}

/**
 * What a stage did, in a sentence.
 * @param {import('./toy-filter.js').StageOutcome} out
 */
function tell(out) {
  const step = `step ${filter.step + (out.stage === 'resample' ? 0 : 1)}`;
  if (out.stage === 'predict') {
    return `${step} · predict: the car drove to ${out.car.toFixed(1)} m, every particle moved by the same command plus noise; the sensor reads ${out.reading.toFixed(1)} m`;
  }
  if (out.stage === 'weigh') {
    return `${step} · weigh: particles near the reading got heavier · ESS ${out.ess.toFixed(0)} of ${filter.x.length}`;
  }
  if (!out.resampled) {
    return `${step} · resample: skipped: ESS ${out.ess.toFixed(0)} > ${out.threshold.toFixed(0)} (the weights are still spread over enough particles)`;
  }
  return `${step} · resample: ESS ${out.ess.toFixed(0)} < ${out.threshold.toFixed(0)}: ${out.distinct} of ${filter.x.length} particles were copied, the rest dropped; all weights now 1/${filter.x.length}`;
}

/**
 * Animates the resampling just done; resolves when it has finished.
 * @param {number[]} before
 * @param {number[]} weightsBefore
 * @param {number[]} parents
 * @returns {Promise<void>}
 */
function animate(before, weightsBefore, parents) {
  return new Promise((resolve) => {
    const t0 = performance.now();
    const shown = { before, weightsBefore, parents };
    animation = shown;
    lesson.animating = true;
    /** @param {number} now */
    const frame = (now) => {
      const t = Math.min(1, (now - t0) / ANIMATION_MS);
      drawView(view, filter, { t, ...shown });
      lesson.animationFrames += 1;
      if (t < 1) {
        requestAnimationFrame(frame);
        return;
      }
      animation = null;
      lesson.animating = false;
      drawAll();
      resolve();
    };
    requestAnimationFrame(frame);
  });
}

let busy = Promise.resolve();
/** Runs the next stage (after any animation in progress). */
function stage() {
  busy = busy.then(async () => {
    const weightsBefore = filter.w;
    const out = filter.advance();
    lesson.stages += 1;
    if (out.stage === 'weigh') history.push({ step: filter.step, ess: out.ess, resampled: false });
    const last = history.at(-1);
    if (out.stage === 'resample' && out.resampled && last) last.resampled = true;
    $('toy-status').textContent = tell(out);
    lesson.last = out;
    drawAll();
    if (out.stage === 'resample' && out.resampled && filter.before && filter.parents) {
      await animate(filter.before, weightsBefore, filter.parents);
    }
  });
  return busy;
}

/** Runs the rest of the current step (a whole step from its start). */
async function step() {
  do await stage(); while (filter.next !== 0);
}

/** @param {boolean} on */
function setPlaying(on) {
  playing = on;
  $('toy-play').textContent = on ? 'Pause' : 'Play';
  clearTimeout(timer);
  if (on) play();
}

async function play() {
  if (!playing) return;
  await stage();
  timer = setTimeout(play, PLAY_STAGE_MS);
}

function restart() {
  setPlaying(false);
  busy = busy.then(() => {
    filter = new ToyFilter(readOptions());
    history = [];
    Object.assign(lesson, { filter, history, last: null, stages: 0 });
    $('toy-status').textContent = 'Particles spread over the whole line: the filter does not know where the car is yet.';
    drawAll();
  });
}

$('toy-play').addEventListener('click', () => setPlaying(!playing));
$('toy-step').addEventListener('click', () => step());
$('toy-stage').addEventListener('click', () => stage());
$('toy-restart').addEventListener('click', restart);
for (const input of form.querySelectorAll('input')) {
  input.addEventListener('input', () => {
    const out = input.nextElementSibling;
    if (out) out.textContent = input.value;
  });
  input.addEventListener('change', restart);
}
document.addEventListener('keydown', (e) => {
  if ((e.target instanceof Element && e.target.closest('input, select, textarea, button')) || e.ctrlKey || e.metaKey || e.altKey) return;
  if (e.key === ' ') {
    e.preventDefault();
    setPlaying(!playing);
  } else if (e.key === '.') {
    step();
  } else if (e.key === ',') {
    stage();
  }
});

drawAll();
document.body.dataset.state = 'running';
