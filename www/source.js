// @ts-check
// The synthetic frame sources: the test road and the simulator's named scenes, rendered inside
// the worker by the wasm module. Each yields frames { rgba, width, height, truth, motion, name,
// index } on demand (see media-source.js for video, images and the webcam).

import { CALTECH } from './camera-presets.js';

/** The camera of the synthetic test road (the Caltech Lanes camera). */
export const DEFAULT_CAMERA = CALTECH;

/** @typedef {import('../pkg/web/lanepf.js').CameraConfig} CameraConfig */
/** @typedef {import('../pkg/worker/index.js').TrackerWorker} TrackerWorker */
/**
 * A frame the worker rendered (worker.js `renderFrame`), with its index and name.
 * @typedef {{ rgba: Uint8ClampedArray<ArrayBuffer>, width: number, height: number,
 *   truth: import('../pkg/web/lanepf.js').LaneEstimate, motion: import('../pkg/web/lanepf.js').EgoMotion | null,
 *   ms: number, index: number, name: string }} SceneFrame
 */

export class TestRoadSource {
  /**
   * @param {TrackerWorker} client the demo's worker
   * @param {CameraConfig} [camera]
   * @param {import('../pkg/web/lanepf.js').TestRoadOptions} [options]
   */
  constructor(client, camera = DEFAULT_CAMERA, options = {}) {
    this.client = client;
    this.camera = camera;
    this.options = options;
    this.index = 0;
    // Frames per second of its motion (the simulator's default; playback is paced at it).
    this.fps = options.fps ?? 30;
    this.label = 'Synthetic test road (straight, dashed markings, known ground truth)';
  }

  async open() {
    return this.client.request('openTestRoad', { camera: this.camera, options: this.options });
  }

  restart() {
    this.index = 0;
  }

  /** Renders the next frame (the test road goes on for ever). */
  async next() {
    const frame = /** @type {SceneFrame} */ (await this.client.request('renderFrame', { index: this.index }));
    frame.index = this.index++;
    frame.name = `${frame.index}`;
    return frame;
  }

  close() {}
}

/** A named scenario of the simulator (curves, lane changes, night, ...). */
export class SceneSource {
  /**
   * @param {TrackerWorker} client the demo's worker
   * @param {import('../pkg/web/lanepf.js').ScenarioName} name
   * @param {string} description
   * @param {import('../pkg/web/lanepf.js').SceneOptions} [options]
   */
  constructor(client, name, description, options = { width: 640, height: 480, seed: 1 }) {
    this.client = client;
    this.name = name;
    this.options = options;
    this.index = 0;
    // Frames per second of the car's motion (the simulator's; a scene has no other rate), playback
    // is paced at it.
    this.fps = 30;
    this.frames = 1;
    /** The scene's camera, once open. */
    /** @type {CameraConfig | null} */
    this.camera = null;
    this.progress = 0;
    this.label = `Synthetic scene “${name}”: ${description}`;
  }

  async open() {
    const info = /** @type {{ width: number, height: number, frames: number, camera: CameraConfig }} */ (
      await this.client.request('openScene', { name: this.name, options: this.options }));
    this.frames = info.frames;
    this.camera = info.camera;
    return info;
  }

  restart() {
    this.index = 0;
    this.progress = 0;
  }

  /** Renders the next frame; null after the scenario's last one. */
  async next() {
    if (this.index >= this.frames) return null;
    const frame = /** @type {SceneFrame} */ (await this.client.request('renderFrame', { index: this.index }));
    frame.index = this.index++;
    frame.name = `${frame.index}`;
    this.progress = this.index / this.frames;
    return frame;
  }

  close() {}
}
