// Reading the demo's canvases in the end-to-end tests.

/** Reads canvas `id` as { width, height, data: number[] } inside the page (a playwright-core
 * page, or a page of the cross-browser drivers, drivers/*.mjs). The pixels cross as one JSON
 * string: as an array of numbers they take ~10 s per 640x480 canvas over WebDriver BiDi
 * (Firefox), where each number is its own object. */
export const readCanvas = async (page, id = 'view') => JSON.parse(await (page.eval ?? page.evaluate).call(page, (id) => {
  const c = document.getElementById(id);
  const d = c.getContext('2d').getImageData(0, 0, c.width, c.height);
  return JSON.stringify({ width: d.width, height: d.height, data: Array.from(d.data) });
}, id));

/** Luma of pixel (x, y) of an image { width, data }. */
export const lum = (img, x, y) => {
  const i = 4 * (Math.round(y) * img.width + Math.round(x));
  return 0.299 * img.data[i] + 0.587 * img.data[i + 1] + 0.114 * img.data[i + 2];
};

/** Brightest luma within +-r px horizontally of (x, y). */
export const peak = (img, x, y, r) => {
  let best = 0;
  for (let dx = -r; dx <= r; dx++) {
    const xx = Math.round(x) + dx;
    if (xx >= 0 && xx < img.width) best = Math.max(best, lum(img, xx, y));
  }
  return best;
};

/** Number of pixels of exactly the colour [r, g, b]. */
export const countColour = (img, [r, g, b]) => {
  let n = 0;
  for (let i = 0; i < img.data.length; i += 4) {
    if (img.data[i] === r && img.data[i + 1] === g && img.data[i + 2] === b) n++;
  }
  return n;
};

/** x of a polyline [[x, y], ...] at row y (linear between points), or null. */
export const xAt = (pts, y) => {
  for (let i = 1; i < pts.length; i++) {
    const [[x0, y0], [x1, y1]] = [pts[i - 1], pts[i]];
    if ((y0 - y) * (y1 - y) <= 0 && y0 !== y1) return x0 + (x1 - x0) * (y - y0) / (y1 - y0);
  }
  return null;
};

/** Number of pixels within `tol` of [r, g, b] in every channel (antialiased lines). */
export const countNear = (img, [r, g, b], tol) => {
  let n = 0;
  for (let i = 0; i < img.data.length; i += 4) {
    if (Math.abs(img.data[i] - r) <= tol && Math.abs(img.data[i + 1] - g) <= tol
      && Math.abs(img.data[i + 2] - b) <= tol) n++;
  }
  return n;
};
