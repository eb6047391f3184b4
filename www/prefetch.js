// @ts-check
// A video fetched ahead (boot.js: the bundled clip while the page's modules load), handed once
// to the reader that opens it (video-select.js). No imports, so boot.js starts it at once.

/** @type {{ url: string, blob: Promise<Blob> } | null} */
let prefetched = null;

/**
 * Starts fetching the video at `url`; the next `takePrefetched(url)` gets its bytes.
 * @param {string} url
 */
export function prefetchVideo(url) {
  const blob = (async () => {
    const res = await fetch(url);
    if (!res.ok) throw new Error(`cannot load ${url}: HTTP ${res.status}`);
    return res.blob();
  })();
  // (A failure is reported by the reader that takes it.)
  blob.catch(() => {});
  prefetched = { url, blob };
}

/**
 * The prefetched bytes of `url` (once; later calls fetch again), or null.
 * @param {string} url
 * @returns {Promise<Blob> | null}
 */
export function takePrefetched(url) {
  if (prefetched?.url !== url) return null;
  const { blob } = prefetched;
  prefetched = null;
  return blob;
}
