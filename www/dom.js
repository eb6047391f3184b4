// @ts-check
// The page's elements, typed: an element the HTML is known to have, of a known kind.

/**
 * The element with this id, which must be a `type` (e.g. HTMLInputElement): throws naming the
 * id when the page has none of that kind, rather than failing later on `null`.
 * @template {Element} T
 * @param {string} id
 * @param {{ new (): T }} type
 * @param {Document} [doc]
 * @returns {T}
 */
export function byId(id, type, doc = document) {
  const el = doc.getElementById(id);
  if (!(el instanceof type)) throw new Error(`#${id}: the page has no ${type.name} with this id`);
  return el;
}

/**
 * The 2-D context of canvas #id (a canvas the page never asks for another kind of context, so
 * `getContext('2d')` cannot be null; throws if it is).
 * @param {string} id
 * @param {Document} [doc]
 */
export function context2d(id, doc = document) {
  const ctx = byId(id, HTMLCanvasElement, doc).getContext('2d');
  if (!ctx) throw new Error(`#${id}: the canvas has no 2-D context`);
  return ctx;
}
