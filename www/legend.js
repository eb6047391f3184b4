// @ts-check
// What the drawing means: the colour legend under the camera view and the estimate's state
// badge on it. The legend's samples are drawn by render.js's own functions with its own
// colours, so the legend cannot say one thing while the canvas shows another.
import { ROLE_COLOURS, drawEstimate, drawTruth, drawHypotheses } from './render.js';

const SAMPLE_W = 56;
const SAMPLE_H = 16;
/**
 * A boundary of `role` across a sample canvas, as image and as road points.
 * @param {import('../pkg/web/lanepf.js').Role} role
 * @param {number} [y]
 * @returns {import('../pkg/web/lanepf.js').Boundary}
 */
const line = (role, y = SAMPLE_H / 2) => ({ role, points: [[4, y], [SAMPLE_W - 4, y]], road_points: [] });

/**
 * The legend's entries: key, label, how to draw the sample (ctx, { byGroup }).
 * @type {{ key: string, label: string, draw: (ctx: CanvasRenderingContext2D, how: { byGroup: boolean }) => void }[]}
 */
const ENTRIES = [
  .../** @type {import('../pkg/web/lanepf.js').Role[]} */ (Object.keys(ROLE_COLOURS)).map((role) => ({
    key: role,
    label: `${role} boundary`,
    /** @param {CanvasRenderingContext2D} ctx */
    draw: (ctx) => drawEstimate(ctx, { valid: true, boundaries: [line(role)] }),
  })),
  {
    key: 'invalid',
    label: 'not valid: the tracker’s guess, faded and dashed',
    draw: (ctx) => drawEstimate(ctx, { valid: false, boundaries: [line('ego-left')] }),
  },
  {
    key: 'truth',
    label: 'ground truth',
    draw: (ctx) => drawTruth(ctx, [line('ego-left')]),
  },
  {
    key: 'particles',
    label: 'particles: thin, coloured by weight, light (blue) to heaviest (yellow)',
    draw: (ctx, { byGroup }) => drawHypotheses(ctx, [0, 0.5, 1].map((weight, k) => ({
      weight, group: k, boundaries: [line(k === 1 ? 'ego-right' : 'ego-left', 3 + 5 * k)],
    })), null, byGroup),
  },
];

export class Legend {
  /**
   * Fills the list `ul` with one item per entry: a sample canvas and its label. Items already
   * in the list (index.html has them, so the page does not move when this runs) are reused:
   * their samples are drawn here and their labels set to the entries' own.
   * @param {HTMLElement} ul
   */
  constructor(ul) {
    /** @type {Map<string, { li: HTMLElement, ctx: CanvasRenderingContext2D, entry: (typeof ENTRIES)[number] }>} */
    this.items = new Map();
    for (const e of ENTRIES) {
      const li = ul.querySelector(`li[data-key="${e.key}"]`) ?? ul.appendChild(document.createElement('li'));
      if (!(li instanceof HTMLElement)) throw new Error(`legend item ${e.key}: not an element`);
      li.dataset.key = e.key;
      const canvas = document.createElement('canvas');
      canvas.width = SAMPLE_W;
      canvas.height = SAMPLE_H;
      canvas.setAttribute('aria-hidden', 'true');
      li.replaceChildren(canvas, ` ${e.label}`);
      const ctx = canvas.getContext('2d');
      if (!ctx) throw new Error('the legend sample has no 2-D context');
      this.items.set(e.key, { li, ctx, entry: e });
    }
    this.update({});
  }

  /**
   * Shows the truth's entry only for a source with ground truth; draws the particles' sample
   * by group when the particles are coloured by group.
   * @param {{ hasTruth?: boolean, byGroup?: boolean }} how
   */
  update({ hasTruth = false, byGroup = false }) {
    for (const { li, ctx, entry } of this.items.values()) {
      ctx.clearRect(0, 0, SAMPLE_W, SAMPLE_H);
      entry.draw(ctx, { byGroup });
      if (entry.key === 'truth') li.hidden = !hasTruth;
      if (entry.key === 'particles') {
        li.childNodes[1].textContent = byGroup
          ? ' particles: thin, coloured by group (model, stage or cluster), heavier more opaque'
          : ` ${entry.label}`;
      }
    }
  }
}

/**
 * The tag on a view saying how many particles are drawn of the tracker's total (hidden with
 * none drawn or no tracker).
 */
/**
 * @param {HTMLElement} tag
 * @param {number} drawn
 * @param {number} total
 */
export function showCount(tag, drawn, total) {
  tag.hidden = !(drawn > 0 && total > 0);
  tag.textContent = tag.hidden ? '' : `particles: ${drawn} of ${total} drawn`;
}

/**
 * The badge on a view: whether the shown estimate is valid; hidden with no estimate.
 * @param {HTMLElement} badge
 * @param {Pick<import('../pkg/web/lanepf.js').LaneEstimate, 'valid'> | null | undefined} estimate
 */
export function showBadge(badge, estimate) {
  badge.hidden = !estimate;
  if (!estimate) return;
  badge.dataset.valid = String(estimate.valid);
  badge.textContent = estimate.valid ? 'valid' : 'no lane: not valid';
  badge.title = estimate.valid
    ? 'The tracker is confident of this frame’s lane; drawn solid.'
    : 'The tracker has no confident lane in this frame; its best guess is drawn faded and dashed.';
}
