// @ts-check
// Which reader a video gets: WebCodecs (webcodecs-source.js: frame-accurate, faster than real
// time) when the browser has a VideoDecoder, the container parses and the decoder takes its
// codec; otherwise the seeking <video> reader of media-source.js. The label says which.
import { VideoSource } from './media-source.js';
import { WebCodecsVideoSource } from './webcodecs-source.js';
import { takePrefetched } from './prefetch.js';

/**
 * The bytes of a video given by URL (the bundled clip), as a Blob: boot.js's prefetch of it
 * when there is one.
 * @param {string} url
 */
async function fetchBlob(url) {
  const early = takePrefetched(url);
  if (early) return early;
  const res = await fetch(url);
  if (!res.ok) throw new Error(`cannot load ${url}: HTTP ${res.status}`);
  return res.blob();
}

/** A video, `file` (a File) or `url`, with VideoSource's options; `pick()` opens a reader for it. */
export class VideoFile {
  /** @param {ConstructorParameters<typeof VideoSource>[0]} options */
  constructor(options) {
    this.options = options;
    this.label = `Video “${options.name}”`;
  }

  /** Opens the video with WebCodecs, else by seeking; returns the opened source. */
  async pick() {
    let why = 'this browser has no WebCodecs VideoDecoder';
    if (typeof VideoDecoder !== 'undefined') {
      let source = null;
      try {
        // (A file, or else a URL, is given.)
        const blob = this.options.file ?? await fetchBlob(/** @type {string} */ (this.options.url));
        source = new WebCodecsVideoSource({ ...this.options, blob });
        await source.open();
        return source;
      } catch (err) {
        source?.close();
        why = err instanceof Error ? err.message : String(err);
      }
    }
    const fallback = new VideoSource(this.options);
    try {
      await fallback.open();
    } catch (err) {
      fallback.close();
      throw new Error(`${err instanceof Error ? err.message : err} (Not WebCodecs: ${why}.)`, { cause: err });
    }
    fallback.label += `, by seeking a <video> element (not WebCodecs: ${why})`;
    return fallback;
  }
}
