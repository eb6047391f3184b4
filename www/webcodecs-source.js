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

/** The first video track of a WebM/Matroska or MP4 `blob` (see the demuxers for the fields). */
export async function demux(blob) {
  const head = new Uint8Array(await blob.slice(0, 12).arrayBuffer());
  if (isWebm(head)) return demuxWebm(blob);
  if (isMp4(head)) return demuxMp4(blob);
  throw new Error('not a WebM, Matroska or MP4 file');
}

export class WebCodecsVideoSource {
  constructor({ blob, name, camera = null, sideBySide = false }) {
    this.blob = blob;
    this.name = name;
    this.camera = camera;
    this.sideBySide = sideBySide;
    this.index = 0;
    this.progress = 0;
    this.label = `Video “${name}”`;
    this.ready = [];
    this.decoder = null;
  }

  /** Demuxes, checks the browser decodes the codec, and decodes the first frame. */
  async open() {
    if (typeof VideoDecoder === 'undefined') throw new Error('this browser has no WebCodecs VideoDecoder');
    const track = await demux(this.blob);
    const config = { codec: track.codec };
    // A size of 0 (a container that gives none) is invalid in a config: left out, the decoder finds it.
    if (track.codedWidth > 0 && track.codedHeight > 0) Object.assign(config, { codedWidth: track.codedWidth, codedHeight: track.codedHeight });
    if (track.description) config.description = track.description;
    let support;
    try {
      support = await VideoDecoder.isConfigSupported(config);
    } catch (err) {
      throw new Error(`the decoder configuration for ${track.codec} is invalid (${err.message})`);
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
    decoder.configure(this.config);
    this.decoder = decoder;
  }

  wake() {
    const waiter = this.waiter;
    this.waiter = null;
    waiter?.();
  }

  /** Resolves on the decoder's next output, dequeue or error; rejects when it stalls. */
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
    const samples = this.track.samples;
    while (this.fed < samples.length && !this.error && this.decoder.decodeQueueSize < DECODE_AHEAD
      && this.ready.length < FRAMES_AHEAD) {
      const k = this.fed++;
      const s = samples[k];
      const data = await this.reader.read(s.offset, s.size, `frame ${k + 1} of ${samples.length}`);
      // EncodedVideoChunk copies the bytes, so a view into the reader's window is enough.
      this.decoder.decode(new EncodedVideoChunk({
        type: s.key ? 'key' : 'delta', timestamp: s.timestamp, duration: s.duration, data,
      }));
    }
  }

  /** The next decoded VideoFrame in presentation order, or null when the stream is done. */
  async decoded() {
    for (;;) {
      if (this.error) throw this.error;
      if (this.ready.length) return this.ready.shift();
      if (this.fed < this.frames) {
        await this.pump();
        if (!this.ready.length && !this.error && this.decoder.decodeQueueSize >= DECODE_AHEAD) await this.wait();
      } else if (!this.flushed) {
        this.flushed = true;
        const decoder = this.decoder;
        let done = false;
        decoder.flush().catch((err) => {
          if (!this.error && decoder === this.decoder) this.error = new Error(`Cannot decode “${this.name}” with WebCodecs: ${err.message}`);
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
    let rgba, right, t;
    try {
      await this.pump(); // keep the decoder busy while the tracker works on this frame
      ({ rgba, right } = this.grabber.grab(frame));
      t = frame.timestamp;
    } finally {
      frame.close();
    }
    const index = this.indexOf.get(t) ?? this.index;
    this.index += 1;
    this.progress = Math.min(1, this.index / this.frames);
    return { rgba, right, width: this.size.width, height: this.size.height, name: `${index}`, index, t: t / 1e6 };
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
