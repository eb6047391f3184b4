// @ts-check
// A bounded run log: a long webcam session must not grow the page's memory without end.

/** Frames kept for export: 10 minutes at 30 fps (a few KB each). */
export const MAX_RESULTS = 18000;

/**
 * Appends `item` to `list`. Once the list is a batch (max / 18, at least 1) over `max`, the
 * oldest entries are dropped so that `max` remain (in batches: one splice per batch, not per
 * frame). Returns how many entries were dropped by this call.
 * @template T
 * @param {T[]} list
 * @param {T} item
 * @param {number} [max]
 */
export function appendCapped(list, item, max = MAX_RESULTS) {
  list.push(item);
  const batch = Math.max(1, Math.ceil(max / 18));
  if (list.length <= max + batch) return 0;
  const drop = list.length - max;
  list.splice(0, drop);
  return drop;
}
