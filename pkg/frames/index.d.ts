// `lanepf/frames`: frames from what a page has, as RGBA bytes for a tracker.
import type { RgbaFrame } from '../web/lanepf.js';

/**
 * What `readFrame` (and `TrackerWorker.step`) accept: RGBA bytes with their size (`ImageData`
 * or `{ data, width, height }`), or something a 2-D canvas can draw.
 */
export type FrameSource =
  | RgbaFrame
  | ImageData
  | ImageBitmap
  | VideoFrame
  | HTMLVideoElement
  | HTMLCanvasElement
  | OffscreenCanvas
  | HTMLImageElement;

/** The size to read a frame at, e.g. the tracker's camera size (default: the source's own). */
export interface ReadOptions {
  width?: number;
  height?: number;
}

/**
 * The RGBA pixels of `source`: an `ImageData` or `RgbaFrame` is returned as it is unless another
 * size is asked for; anything else is drawn on a reused canvas (an OffscreenCanvas where there is
 * one) and read back as a new `ImageData`. Throws an `Error` named `LanepfInputError` for an
 * unsupported source, a `<video>` with no frame yet, an image not loaded or a bad size.
 */
export function readFrame(source: FrameSource, options?: ReadOptions): ImageData | RgbaFrame;

/** The size `source` shows in pixels, `[width, height]`, or `null` for what `readFrame` refuses. */
export function sourceSize(source: unknown): [number, number] | null;

/** What `FrameReader` hands `onFrame` with each frame. */
export interface FrameInfo {
  /** The frame's presentation time in the media, seconds (the canvas clock for a canvas). */
  mediaTime: number;
  /** Frames read so far, this one included. */
  frames: number;
}

/**
 * Reads a playing `<video>` (or a canvas) once per presented frame, with
 * `requestVideoFrameCallback` (`requestAnimationFrame` where there is none).
 */
export class FrameReader {
  constructor(source: HTMLVideoElement | HTMLCanvasElement | OffscreenCanvas, options?: ReadOptions);
  /** Frames read so far. */
  readonly frames: number;
  /** Whether frames are timed by `requestVideoFrameCallback`. */
  readonly usesVideoFrameCallback: boolean;
  /** The frame showing now. */
  read(): ImageData;
  /**
   * Calls `onFrame` for every presented frame; a returned promise is awaited before the next
   * frame is read (a slow consumer skips frames). Resolves when `stop()` is called or the video
   * ends; rejects with the first error thrown.
   */
  start(onFrame: (frame: ImageData, info: FrameInfo) => void | Promise<void>): Promise<void>;
  /** Stops reading. */
  stop(): void;
}
