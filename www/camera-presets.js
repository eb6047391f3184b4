// @ts-check
// The camera a tracker gets for a source: the bundled clip's own calibration, a camera file the
// user imports, or, for other media, the clip's camera scaled to the frame size (a guess that
// a dash cam sees about as much as the Udacity one; the status line says so).

export const CLIP = {
  url: 'clips/udacity-project-640x360.webm',
  camera: 'clips/udacity-project-640x360.camera.json',
  name: 'Udacity project_video.mp4, 0-12 s',
  fps: 25,
};

/** @typedef {import('../pkg/web/lanepf.js').CameraConfig} CameraConfig */

/** @type {Promise<CameraConfig> | null} */
let clipCamera = null;

/**
 * The bundled clip's camera (fetched once from the page's own files; a failed fetch is tried
 * again on the next call).
 * @returns {Promise<CameraConfig>}
 */
export function loadClipCamera() {
  clipCamera ??= (async () => {
    const res = await fetch(CLIP.camera);
    if (!res.ok) throw new Error(`cannot load ${CLIP.camera}: HTTP ${res.status}`);
    return /** @type {CameraConfig} */ (await res.json());
  })();
  clipCamera.catch(() => { clipCamera = null; });
  return clipCamera;
}

/**
 * `camera` rescaled to width x height (intrinsics scale with the image; pose is kept).
 * @param {CameraConfig} camera
 * @param {number} width
 * @param {number} height
 * @returns {CameraConfig}
 */
export function scaleCamera(camera, width, height) {
  const sx = width / camera.width;
  const sy = height / camera.height;
  return {
    ...camera,
    width,
    height,
    fx: camera.fx * sx,
    fy: camera.fy * sy,
    cx: (camera.cx + 0.5) * sx - 0.5,
    cy: (camera.cy + 0.5) * sy - 0.5,
  };
}

/**
 * Reads a camera.json file; throws an Error a person can act on.
 * @param {File} file
 * @returns {Promise<CameraConfig>}
 */
export async function readCameraFile(file) {
  let value;
  try {
    value = JSON.parse(await file.text());
  } catch (err) {
    throw new Error(`“${file.name}” is not JSON: ${err instanceof Error ? err.message : err}`, { cause: err });
  }
  for (const key of ['width', 'height', 'fx', 'fy', 'cx', 'cy', 'height_m', 'pitch_deg']) {
    if (!Number.isFinite(value?.[key])) {
      throw new Error(`“${file.name}” is not a camera file: “${key}” is missing or not a number`);
    }
  }
  return value;
}

/** The Caltech Lanes camera (640x480, 2.18 m, 14 deg down; also the simulator's default). */
export const CALTECH = {
  width: 640, height: 480, fx: 309.4362, fy: 344.2161, cx: 317.9034, cy: 256.5352,
  height_m: 2.1798, pitch_deg: 14.0, yaw_deg: 0.0, roll_deg: 0.0,
};

/** @type {Promise<Record<string, { label: string, camera: CameraConfig }>> | null} */
let presetsLoading = null;

/**
 * Camera presets for the calibration panel: { key: { label, camera } }, their files fetched
 * side by side, once (boot.js starts this while the page's modules load).
 */
export function loadPresets() {
  presetsLoading ??= fetchPresets();
  return presetsLoading;
}

async function fetchPresets() {
  const files = {
    'udacity-640': ['Udacity clip (640x360)', CLIP.camera],
    'udacity-1280': ['Udacity project video (1280x720)', 'clips/udacity-1280x720.camera.json'],
    'udacity-challenge': ['Udacity challenge video (1280x720)', 'clips/udacity-challenge-1280x720.camera.json'],
    'udacity-960': ['Udacity 960x540 videos (assumed)', 'clips/udacity-960x540.camera.json'],
    kitti: ['KITTI object demo pair (stereo, 1242x375)', 'cameras/kitti-object-demo.camera.json'],
    karlsruhe: ['Karlsruhe urban pairs (stereo, 1344x391)', 'cameras/karlsruhe-urban.camera.json'],
  };
  /** @type {Record<string, { label: string, camera: CameraConfig }>} */
  const presets = { caltech: { label: 'Caltech Lanes (640x480)', camera: CALTECH } };
  const fetched = await Promise.all(Object.entries(files).map(async ([key, [label, url]]) => {
    const res = await fetch(url);
    return res.ok ? { key, label, camera: /** @type {CameraConfig} */ (await res.json()) } : null;
  }));
  // (In the files' order, as the panel's menu lists them.)
  for (const p of fetched) if (p) presets[p.key] = { label: p.label, camera: p.camera };
  return presets;
}
