// @ts-check
// One tracker's weight histogram and belief view (the main tracker's, or compare mode's second
// tracker's in figures of its own), drawn from what the worker sent with the frame or stage:
// `{ weighing, particles, layers }` and the estimate. Returns what the end-to-end tests read.
import { byId } from './dom.js';
import { drawWeights } from './weights.js';
import { beliefPanels, drawBelief } from './belief.js';

/**
 * Draws `part` of tracker `trackerId` into the figures named by `ids` (`{ weights, belief }`:
 * the canvases' ids; each figure is `${id}-figure` with a `${id}-caption`), after `label`
 * ("after the whole frame", "after “predict”"); `shown`: the plots are on. Hides the figures
 * when there is nothing to draw.
 * @param {{ weights: string, belief: string, named?: boolean }} ids
 * @param {string} trackerId
 * @param {{ weighing?: { weights: Float32Array, count: number, ess: number, group: number | null },
 *   particles?: { data: Float32Array, stride: number } | null, layers?: import('../pkg/web/lanepf.js').Layer[] | null }
 *   | null | undefined} part what the worker sent with the frame or stage
 * @param {import('../pkg/web/lanepf.js').LaneEstimate | null | undefined} estimate
 * @param {string} label
 * @param {boolean} shown
 */
export function showWeighing(ids, trackerId, part, estimate, label, shown) {
  /** @param {string} id */
  const el = (id) => byId(id, HTMLElement);
  /** @param {string} id */
  const canvas = (id) => byId(id, HTMLCanvasElement);
  const weighing = part?.weighing ?? null;
  el(`${ids.weights}-figure`).hidden = !weighing || !shown;
  if (!weighing) {
    el(`${ids.belief}-figure`).hidden = true;
    return { weighing: null, belief: null };
  }
  const who = ids.named ? `${trackerId}: ` : '';
  el(`${ids.weights}-caption`).textContent = who + drawWeights(canvas(ids.weights), weighing, label);
  const record = { ...weighing, weights: undefined, n: weighing.weights.length, label };
  // The paper's own view of the belief, from the same particles.
  const p = part?.particles;
  const panels = p ? beliefPanels(trackerId, p.data, p.stride, estimate, part?.layers) : [];
  el(`${ids.belief}-figure`).hidden = !panels.length || !shown;
  if (!panels.length) return { weighing: record, belief: null };
  drawBelief(canvas(ids.belief), panels);
  el(`${ids.belief}-caption`).textContent = `${trackerId}’s belief ${label}: `
    + `${panels.map((q) => (q.colours ? `${q.title} (${q.colours})` : q.title)).join('; then ')}.`;
  const belief = panels.map((q) => ({ title: q.title, unit: q.unit, items: q.items.length,
    markers: q.markers.map((m) => m.label), probabilities: q.probabilities ?? null }));
  return { weighing: record, belief };
}
