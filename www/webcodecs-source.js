// @ts-check
// A video decoded with WebCodecs: the container is demuxed here (demux-webm.js, demux-mp4.js),
// the samples are read from the file by offset and decoded by a VideoDecoder, and the frames
// come out in presentation order with the container's timestamps: frame-accurate, and as fast
// as the decoder and the tracker go. The same interface as media-source.js's VideoSource.
import { BlobReader } from './blob-reader.js';
import { demuxWebm, isWebm } from './demux-webm.js';
import { demuxMp4, isMp4 } from './demux-mp4.js';
import { Grabber, frameSize, sizeNote } from './media-source.js';

/** Chunks queued in the decoder at most, and decoded frames waiting to be read. */
const DECODE_AHEAD = 4;
const FRAMES_AHEAD = 3;
/** A decoder that gives nothing for this long is reported, not waited on for ever. */
const STALL_MS = 20000;

/**
 * A demuxed video track: samples in decode order, timestamps and durations in µs.
 * @typedef {{ container: string, codec: string, description?: Uint8Array | null, codedWidth: number,
 *   codedHeight: number, duration: number, fps: number | null,
 *   samples: { timestamp: number, duration: number, key: boolean, offset: number, size: number }[] }} Track
 */

/**
 * The first video track of a WebM/Matroska or MP4 `blob` (see the demuxers for the fields).
 * @param {Blob} blob
 * @returns {Promise<Track>}
 */
export async function demux(blob) {
  const head = new Uint8Array(await blob.slice(0, 12).arrayBuffer());
  if (isWebm(head)) return demuxWebm(blob);
  if (isMp4(head)) return demuxMp4(blob);
  throw new Error('not a WebM, Matroska or MP4 file');
}

export class WebCodecsVideoSource {
  /** @param {{ blob: Blob, name: string, camera?: import('../pkg/web/lanepf.js').CameraConfig | null, sideBySide?: boolean }} source */
  constructor({ blob, name, camera = null, sideBySide = false }) {
    this.blob = blob;
    this.name = name;
    this.camera = camera;
    this.sideBySide = sideBySide;
    this.index = 0;
    this.progress = 0;
    this.label = `Video “${name}”`;
    /** Decoded frames waiting to be read, in presentation order. */
    /** @type {VideoFrame[]} */
    this.ready = [];
    /** @type {VideoDecoder | null} */
    this.decoder = null;
    // Set by `open` (the track, its decoder config and reader, each timestamp's frame index,
    // the picture size) and by `start` (samples fed, flushed, the decoder's error).
    /** @type {Track | null} */
    this.track = null;
    /** @type {VideoDecoderConfig | null} */
    this.config = null;
    /** @type {BlobReader | null} */
    this.reader = null;
    /** @type {Map<number, number>} */
    this.indexOf = new Map();
    /** @type {{ width: number, height: number } | null} */
    this.size = null;
    /** @type {Grabber | null} */
    this.grabber = null;
    /** @type {Error | null} */
    this.error = null;
    this.frames = 0;
    /** @type {number | null} */
    this.fps = null;
    this.fed = 0;
    this.flushed = false;
    /** Called on the decoder's next output, dequeue or error (see `wait`). */
    /** @type {(() => void) | null} */
    this.waiter = null;
  }

  /** Demuxes, checks the browser decodes the codec, and decodes the first frame. */
  async open() {
    if (typeof VideoDecoder === 'undefined') throw new Error('this browser has no WebCodecs VideoDecoder');
    const track = await demux(this.blob);
    /** @type {VideoDecoderConfig} */
    const config = { codec: track.codec };
    // A size of 0 (a container that gives none) is invalid in a config: left out, the decoder finds it.
    if (track.codedWidth > 0 && track.codedHeight > 0) Object.assign(config, { codedWidth: track.codedWidth, codedHeight: track.codedHeight });
    if (track.description) config.description = track.description;
    let support;
    try {
      support = await VideoDecoder.isConfigSupported(config);
    } catch (err) {
      throw new Error(`the decoder configuration for ${track.codec} is invalid (${err instanceof Error ? err.message : err})`, { cause: err });
    }
    if (!support.supported) throw new Error(`this browser's VideoDecoder does not decode ${track.codec}`);
    // Each frame's index in presentation order, by its timestamp.
    const shown = track.samples.map((s) => s.timestamp).sort((a, b) => a - b);
    this.indexOf = new Map(shown.map((t, k) => [t, k]));
    if (this.indexOf.size !== shown.length) throw new Error('two frames of the video share a timestamp');
    this.track = track;
    this.config = config;
    this.reader = new BlobReader(this.blob);
    this.frames = track.samples.length;
    this.fps = track.fps ?? Math.round((100 * this.frames) / track.duration) / 100;
    this.start();
    // The first frame gives the picture size (and proves the stream decodes).
    const first = await this.decoded();
    if (!first) throw new Error('the decoder gave no frame');
    this.ready.unshift(first);
    const [width, height] = [first.displayWidth, first.displayHeight];
    this.size = frameSize(width, height, this.sideBySide);
    this.grabber = new Grabber(this.size.width, this.size.height, this.sideBySide);
    this.label = `Video “${this.name}”: ${width}x${height}, ${track.duration.toFixed(1)} s, `
      + `${this.frames} frames at ${this.fps} frames/s, decoded with WebCodecs (${track.codec})`
      + sizeNote(this.size, width, this.sideBySide);
  }

  /** A new decoder from the first sample (a keyframe; the demuxers check it). */
  start() {
    this.dropFrames();
    if (this.decoder && this.decoder.state !== 'closed') this.decoder.close();
    this.fed = 0;
    this.flushed = false;
    this.error = null;
    const decoder = new VideoDecoder({
      output: (frame) => {
        if (decoder !== this.decoder) {
          frame.close();
          return;
        }
        this.ready.push(frame);
        this.wake();
      },
      error: (err) => {
        if (decoder !== this.decoder) return;
        this.error = new Error(`Cannot decode “${this.name}” with WebCodecs: ${err.message}`);
        this.wake();
      },
    });
    decoder.addEventListener('dequeue', () => this.wake());
    if (!this.config) throw new Error(`“${this.name}” is not open`);
    decoder.configure(this.config);
    this.decoder = decoder;
  }

  wake() {
    const waiter = this.waiter;
    this.waiter = null;
    waiter?.();
  }

  /** Resolves on the decoder's next output, dequeue or error; rejects when it stalls. */
  /** @returns {Promise<void>} */
  wait() {
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.waiter = null;
        reject(new Error(`Cannot decode “${this.name}”: the decoder gave nothing for ${STALL_MS / 1000} s`));
      }, STALL_MS);
      this.waiter = () => {
        clearTimeout(timer);
        resolve();
      };
    });
  }

  /** Queues samples while the decoder's queue and the decoded frames stay short. */
  async pump() {
    const { track, reader } = this;
    if (!track || !reader) throw new Error(`“${this.name}” is not open`);
    const samples = track.samples;
    while (this.fed < samples.length && !this.error && this.decoder && this.decoder.decodeQueueSize < DECODE_AHEAD
      && this.ready.length < FRAMES_AHEAD) {
      const k = this.fed++;
      const s = samples[k];
      const data = await reader.read(s.offset, s.size, `frame ${k + 1} of ${samples.length}`);
      // EncodedVideoChunk copies the bytes, so a view into the reader's window is enough.
      // (The decoder now: `restart` may have replaced it meanwhile.)
      this.decoder?.decode(new EncodedVideoChunk({
        type: s.key ? 'key' : 'delta', timestamp: s.timestamp, duration: s.duration, data,
      }));
    }
  }

  /**
   * The next decoded VideoFrame in presentation order, or null when the stream is done.
   * @returns {Promise<VideoFrame | null>}
   */
  async decoded() {
    for (;;) {
      if (this.error) throw this.error;
      const frame = this.ready.shift();
      if (frame) return frame;
      const decoder = this.decoder;
      if (!decoder) throw new Error(`“${this.name}” is not open`);
      if (this.fed < this.frames) {
        await this.pump();
        if (!this.ready.length && !this.error && decoder.decodeQueueSize >= DECODE_AHEAD) await this.wait();
      } else if (!this.flushed) {
        this.flushed = true;
        let done = false;
        decoder.flush().catch((err) => {
          if (!this.error && decoder === this.decoder) this.error = new Error(`Cannot decode “${this.name}” with WebCodecs: ${err instanceof Error ? err.message : err}`);
        }).finally(() => {
          done = true;
          this.wake();
        });
        while (!done && !this.error) await this.wait();
      } else {
        return null;
      }
    }
  }

  restart() {
    this.index = 0;
    this.progress = 0;
    this.start();
  }

  async next() {
    const frame = await this.decoded();
    if (!frame) return null;
    const { grabber, size } = this;
    if (!grabber || !size) throw new Error(`“${this.name}” is not open`);
    let rgba, right, t;
    try {
      await this.pump(); // keep the decoder busy while the tracker works on this frame
      ({ rgba, right } = grabber.grab(frame));
      t = frame.timestamp;
    } finally {
      frame.close();
    }
    const index = this.indexOf.get(t) ?? this.index;
    this.index += 1;
    this.progress = Math.min(1, this.index / this.frames);
    return { rgba, right, width: size.width, height: size.height, name: `${index}`, index, t: t / 1e6 };
  }

  dropFrames() {
    for (const f of this.ready) f.close();
    this.ready = [];
  }

  close() {
    this.dropFrames();
    if (this.decoder && this.decoder.state !== 'closed') this.decoder.close();
    this.decoder = null;
    this.error = new Error(`“${this.name}” was closed`);
    this.wake();
  }
}
