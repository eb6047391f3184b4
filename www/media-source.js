// Frame sources from media the browser decodes: a video (the bundled clip or a file of the
// user's), still images, the webcam. Each yields frames { rgba, width, height, name } in order,
// and null at the end. Frames are read from a canvas the size the tracker works at.

/** Largest frame width handed to a tracker; wider media are scaled down (aspect kept). */
export const MAX_WIDTH = 960;

function workSize(width, height) {
  if (!(width > 0 && height > 0)) throw new Error('the media reports no picture size');
  const s = Math.min(1, MAX_WIDTH / width);
  return { width: Math.round(width * s), height: Math.round(height * s) };
}

/**
 * Reads frames of width x height from images, videos or cameras. With `sideBySide`, a source
 * picture holds the left camera's frame on its left half and the right camera's on its right
 * half; `grab` then returns both.
 */
export class Grabber {
  constructor(width, height, sideBySide = false) {
    this.canvas = new OffscreenCanvas(sideBySide ? 2 * width : width, height);
    this.ctx = this.canvas.getContext('2d', { willReadFrequently: true });
    this.width = width;
    this.height = height;
    this.sideBySide = sideBySide;
  }

  grab(image) {
    this.ctx.drawImage(image, 0, 0, this.canvas.width, this.height);
    const rgba = this.ctx.getImageData(0, 0, this.width, this.height).data;
    const right = this.sideBySide ? this.ctx.getImageData(this.width, 0, this.width, this.height).data : null;
    return { rgba, right };
  }
}

/** The frame size of a picture, halved across for side-by-side stereo. */
export function frameSize(width, height, sideBySide) {
  return workSize(sideBySide ? width / 2 : width, height);
}

/** The label's note on the frame size the tracker gets, when it is not the picture's own. */
export function sizeNote(size, width, sideBySide) {
  if (sideBySide) return `, side-by-side stereo of ${size.width}x${size.height}`;
  return size.width !== width ? `, tracked at ${size.width}x${size.height}` : '';
}

/** Waits for `ok` on `target`; rejects on `bad` or after `ms` milliseconds. */
function once(target, ok, bad, ms, what) {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => { done(); reject(new Error(`${what}: timed out`)); }, ms);
    const onOk = () => { done(); resolve(); };
    const onBad = () => { done(); reject(new Error(what)); };
    function done() {
      clearTimeout(timer);
      target.removeEventListener(ok, onOk);
      if (bad) target.removeEventListener(bad, onBad);
    }
    target.addEventListener(ok, onOk);
    if (bad) target.addEventListener(bad, onBad);
  });
}

/**
 * The video's frame rate, measured: play it muted at quarter speed for a few frames and take the
 * shortest interval between the media times of presented frames (requestVideoFrameCallback).
 * (At full speed a slow compositor presents only some frames: WebKit on a loaded machine
 * showed every 4th, and the rate read as 6.25 instead of 25.) Null when the browser lacks that
 * callback or the video does not play.
 */
async function measureFps(video) {
  if (!('requestVideoFrameCallback' in video)) return null;
  const times = [];
  const measured = new Promise((resolve) => {
    const onFrame = (_, meta) => {
      times.push(meta.mediaTime);
      if (times.length < 8) video.requestVideoFrameCallback(onFrame);
      else resolve();
    };
    video.requestVideoFrameCallback(onFrame);
  });
  try {
    video.playbackRate = 0.25;
    await video.play();
    await Promise.race([measured, new Promise((r) => setTimeout(r, 3000))]);
  } catch {
    return null;
  } finally {
    video.pause();
    video.playbackRate = 1;
  }
  let best = Infinity;
  for (let i = 1; i < times.length; i++) {
    const dt = times[i] - times[i - 1];
    if (dt > 1e-3) best = Math.min(best, dt);
  }
  // Common rates are whole or NTSC (x/1.001) numbers; keep two decimals.
  return Number.isFinite(best) ? Math.round(100 / best) / 100 : null;
}

/** A MediaRecorder file reports an infinite duration until the browser has seen its end. */
async function knownDuration(video) {
  if (Number.isFinite(video.duration)) return video.duration;
  const changed = once(video, 'durationchange', 'error', 10000, 'the video has no known duration');
  video.currentTime = 1e101;
  await changed;
  video.currentTime = 0;
  return video.duration;
}

const MEDIA_ERRORS = {
  1: 'loading was aborted',
  2: 'a network error stopped the download',
  3: 'the file is corrupt or uses a feature this browser cannot decode',
  4: 'this browser cannot play this format',
};

/**
 * A video processed offline, frame by frame in order: seek to the next frame's time, wait for
 * it to be decoded, read it. Faster or slower than real time as the tracker allows; `fps` is
 * the stepping rate: the video's own, given or measured.
 */
export class VideoSource {
  constructor({ url, file = null, name, fps = null, camera = null, sideBySide = false }) {
    this.file = file;
    this.sideBySide = sideBySide;
    this.url = url ?? URL.createObjectURL(file);
    this.name = name;
    this.fps = fps;
    this.camera = camera;
    this.index = 0;
    this.progress = 0;
    this.label = `Video “${name}”`;
  }

  async open() {
    const video = document.createElement('video');
    video.muted = true;
    video.playsInline = true;
    video.preload = 'auto';
    video.src = this.url;
    try {
      await once(video, 'loadeddata', 'error', 15000, 'the video did not load');
    } catch (err) {
      const why = MEDIA_ERRORS[video.error?.code] ?? err.message;
      throw new Error(`Cannot open “${this.name}”: ${why}. Try an H.264 MP4 or a VP9 WebM.`);
    }
    const duration = await knownDuration(video).catch(() => NaN);
    if (!(duration > 0) || !Number.isFinite(duration)) {
      throw new Error(`Cannot open “${this.name}”: it has no known duration (a live stream?).`);
    }
    // Unknown rate: measure it; failing that, read 30 frames per second (and say so).
    this.fpsNote = '';
    if (!this.fps) {
      const measured = await measureFps(video);
      this.fps = measured ?? 30;
      this.fpsNote = measured ? ' (measured)' : ' (assumed: the browser did not report its frames)';
    }
    this.video = video;
    this.size = frameSize(video.videoWidth, video.videoHeight, this.sideBySide);
    this.grabber = new Grabber(this.size.width, this.size.height, this.sideBySide);
    this.frames = Math.max(1, Math.floor(video.duration * this.fps));
    this.label = `Video “${this.name}”: ${video.videoWidth}x${video.videoHeight}, `
      + `${video.duration.toFixed(1)} s, read at ${this.fps} frames/s${this.fpsNote}`
      + sizeNote(this.size, video.videoWidth, this.sideBySide);
  }

  restart() {
    this.index = 0;
    this.progress = 0;
  }

  async next() {
    if (this.index >= this.frames) return null;
    const video = this.video;
    // The middle of frame `index`, so rounding never lands on its neighbour.
    const t = Math.min((this.index + 0.5) / this.fps, video.duration - 1e-3);
    if (Math.abs(video.currentTime - t) > 1e-6) {
      const seeked = once(video, 'seeked', 'error', 10000, `cannot decode “${this.name}” at ${t.toFixed(2)} s`);
      video.currentTime = t;
      await seeked;
    }
    const { rgba, right } = this.grabber.grab(video);
    const index = this.index++;
    this.progress = this.index / this.frames;
    return { rgba, right, width: this.size.width, height: this.size.height, name: `${index}`, index, t };
  }

  close() {
    this.video?.removeAttribute('src');
    this.video?.load();
    if (this.file) URL.revokeObjectURL(this.url);
  }
}

/** The name with its camera token (`left`/`right`, or `l`/`r` between separators) as `*`. */
const cameraless = (name) => name.replace(/left|right/i, '*').replace(/(^|[_.\-])[lr](?=[_.\-])/i, '$1*');

/** Whether sorted `files` are left/right pairs: names that differ only in their camera token. */
export function arePairs(names) {
  if (names.length % 2 !== 0) return false;
  for (let k = 0; k < names.length; k += 2) {
    const [a, b] = [names[k], names[k + 1]];
    if (a === b || cameraless(a) === a || cameraless(a) !== cameraless(b)) return false;
  }
  return true;
}

/**
 * Still images (one or a sequence, in file-name order), each a frame. Stereo (`stereo`):
 * images whose names pair up as left and right (`x_left`/`x_right`, `x_l`/`x_r`) are stereo
 * pairs; otherwise every image is a side-by-side picture.
 */
export class ImageSource {
  constructor(files, { camera = null, stereo = false } = {}) {
    this.files = [...files].sort((a, b) => a.name.localeCompare(b.name, undefined, { numeric: true }));
    this.camera = camera;
    this.pairs = stereo && arePairs(this.files.map((f) => f.name));
    this.sideBySide = stereo && !this.pairs;
    this.step = this.pairs ? 2 : 1;
    this.index = 0;
    this.progress = 0;
    const n = this.files.length / this.step;
    const what = this.pairs ? 'stereo pair' : this.sideBySide ? 'side-by-side stereo image' : 'image';
    this.label = n === 1 ? `${what} “${this.files[0].name}”` : `${n} ${what}s, “${this.files[0].name}” first`;
    this.label = this.label[0].toUpperCase() + this.label.slice(1);
  }

  async decode(file) {
    try {
      return await createImageBitmap(file);
    } catch {
      throw new Error(`Cannot decode “${file.name}”: not an image this browser reads (JPEG, PNG, WebP).`);
    }
  }

  async open() {
    const first = await this.decode(this.files[0]);
    this.size = frameSize(first.width, first.height, this.sideBySide);
    this.first = first;
    this.grabber = new Grabber(this.size.width, this.size.height, this.sideBySide);
  }

  restart() {
    this.index = 0;
    this.progress = 0;
  }

  /** Reads image `k`, which must have the first image's size. */
  async read(k) {
    const file = this.files[k];
    const bitmap = k === 0 && this.first ? this.first : await this.decode(file);
    const expected = frameSize(bitmap.width, bitmap.height, this.sideBySide);
    if (expected.width !== this.size.width || expected.height !== this.size.height) {
      throw new Error(`“${file.name}” is ${bitmap.width}x${bitmap.height}; a sequence must keep `
        + `the size of its first image (${this.files[0].name})`);
    }
    const out = this.grabber.grab(bitmap);
    if (bitmap !== this.first) bitmap.close();
    return out;
  }

  async next() {
    if (this.index >= this.files.length) return null;
    const k = this.index;
    const { rgba, right } = await this.read(k);
    const frame = { rgba, right, width: this.size.width, height: this.size.height, name: this.files[k].name };
    if (this.pairs) frame.right = (await this.read(k + 1)).rgba;
    this.index += this.step;
    this.progress = this.index / this.files.length;
    return { ...frame, index: k / this.step };
  }

  close() {
    this.first?.close();
  }
}

/** The webcam, live: each frame is whatever the camera shows when the tracker is ready. */
export class WebcamSource {
  constructor(camera = null) {
    this.camera = camera;
    this.index = 0;
    this.progress = null;
    this.label = 'Webcam';
  }

  async open() {
    if (!navigator.mediaDevices?.getUserMedia) {
      throw new Error('This browser offers no camera access here (it needs https or localhost).');
    }
    try {
      this.stream = await navigator.mediaDevices.getUserMedia({
        video: { width: { ideal: 640 }, height: { ideal: 480 } }, audio: false,
      });
    } catch (err) {
      if (err.name === 'NotAllowedError' || err.name === 'SecurityError') {
        throw new Error('Camera permission was refused. Allow the camera for this page and choose Webcam again.');
      }
      if (err.name === 'NotFoundError' || err.name === 'OverconstrainedError') {
        throw new Error('No camera was found on this device.');
      }
      throw new Error(`The camera could not be started: ${err.message}`);
    }
    const video = document.createElement('video');
    video.muted = true;
    video.playsInline = true;
    video.srcObject = this.stream;
    await video.play();
    if (!video.videoWidth) await once(video, 'resize', null, 5000, 'the camera sent no picture');
    this.video = video;
    this.size = frameSize(video.videoWidth, video.videoHeight, this.sideBySide);
    this.grabber = new Grabber(this.size.width, this.size.height, this.sideBySide);
    const track = this.stream.getVideoTracks()[0];
    this.label = `Webcam “${track?.label || 'camera'}”: ${video.videoWidth}x${video.videoHeight}`;
  }

  restart() {
    this.index = 0;
  }

  async next() {
    const { rgba } = this.grabber.grab(this.video);
    const index = this.index++;
    const t = performance.now() / 1000;
    return { rgba, width: this.size.width, height: this.size.height, name: `${index}`, index, t };
  }

  close() {
    for (const t of this.stream?.getTracks() ?? []) t.stop();
  }
}
