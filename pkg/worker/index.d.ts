// `lanepf/worker`: a Tracker in a module Web Worker, behind promises.
import type {
  EgoMotion, Hypothesis, LaneEstimate, Layer, ResampleDecision, TrackerConfig, TrackerId,
} from '../web/lanepf.js';
import type { FrameSource } from '../frames/index.js';

export type { FrameSource } from '../frames/index.js';

/** How `TrackerWorker.create` starts the worker. */
export interface TrackerWorkerOptions {
  /** A Worker running this package's `worker/worker.js`, or one of your own that calls `serve()`
   *  of `lanepf/worker/serve.js` (default: one is started with
   *  `new Worker(new URL('./worker.js', import.meta.url), { type: 'module' })`). */
  worker?: Worker;
  /** Where the worker fetches `lanepf_bg.wasm` (default: next to the package's `web/lanepf.js`). */
  wasm?: string | URL;
}

/** What `step`, `track` and `beginFrame` take besides the frame. */
export interface WorkerStepOptions {
  /** The right camera's frame (`danescu-stereo`), read at the left frame's size. */
  right?: FrameSource;
  /** The car's motion at this frame (the Danescu trackers drift by it; the others ignore it). */
  motion?: EgoMotion;
  /** Read the frame at this size (e.g. the camera's) rather than the source's own. */
  width?: number;
  height?: number;
  /** Send a copy of an ImageData's pixels; by default its buffer is transferred and the
   *  ImageData is empty (detached) afterwards. */
  copy?: boolean;
}

/** What `track` returns besides the estimate. */
export interface TrackWant {
  /** At most this many particles drawn as lane hypotheses. */
  hypotheses?: number;
  /** The particle cloud (`particleStride` numbers per particle). */
  particles?: boolean;
  /** The tracker's cues after the frame. */
  layers?: boolean;
  /** The frame's resampling decisions, as the filters made them. */
  resamplings?: boolean;
  /** The frame's pixels back (transferred), e.g. to draw it. */
  frame?: boolean;
}

/** The result of `track`. */
export interface TrackResult {
  estimate: LaneEstimate;
  /** Milliseconds the step took in the worker. */
  ms: number;
  hypotheses?: Hypothesis[];
  particles?: Float32Array;
  layers?: Layer[];
  resamplings?: ResampleDecision[];
  frame?: { data: Uint8ClampedArray<ArrayBuffer> | Uint8Array<ArrayBuffer>; width: number; height: number };
}

/**
 * A Tracker running in its own module worker (its own wasm instance). Calls are answered in
 * order. A rejected call's Error carries lanepf's kind in `name` (`LanepfConfigError`,
 * `LanepfInputError`, `LanepfStateError`).
 */
export class TrackerWorker {
  /** Starts the worker with no tracker yet (`open` builds one); for a worker of your own. */
  static connect(options?: TrackerWorkerOptions): Promise<TrackerWorker>;
  /** Starts the worker and builds the tracker; rejects with the constructor's Error. `config`
   *  takes tracker `id`'s options (`TrackerConfig<Id>`), as `new Tracker(id, config)` does. */
  static create<Id extends TrackerId>(id: Id, config: TrackerConfig<Id>, options?: TrackerWorkerOptions): Promise<TrackerWorker>;
  private constructor(worker: Worker);
  /** The package's version, as the worker reports it. */
  readonly version: string;
  /** The tracker's id (undefined while no tracker is open). */
  readonly id: TrackerId;
  readonly isStereo: boolean;
  readonly particleStride: number;
  readonly stepNames: string[];
  /** Tracks one frame. The frame's pixels are transferred to the worker. */
  step(frame: FrameSource, options?: WorkerStepOptions): Promise<LaneEstimate>;
  /** As `step`, with the step's time and what `want` asks for. */
  track(frame: FrameSource, options?: WorkerStepOptions & { want?: TrackWant }): Promise<TrackResult>;
  /** Starts a frame in per-step mode. */
  beginFrame(frame: FrameSource, options?: WorkerStepOptions): Promise<void>;
  /** The next filter step: the estimate after the last, `null` before it. */
  advance(): Promise<LaneEstimate | null>;
  /** Index into `stepNames` of the next step, `null` when no frame is in progress. */
  nextStep(): Promise<number | null>;
  reset(): Promise<void>;
  particles(): Promise<Float32Array>;
  hypotheses(max: number): Promise<Hypothesis[]>;
  layers(): Promise<Layer[]>;
  /** The resampling decisions of the last `step` / `advance`, as the filters made them. */
  resamplings(): Promise<ResampleDecision[]>;
  /** Replaces the tracker in the same worker (same wasm instance); rejects as `create` does. */
  open<Id extends TrackerId>(id: Id, config: TrackerConfig<Id>): Promise<this>;
  /** Frees the tracker, keeping the worker. */
  close(): Promise<void>;
  /** Sends a request to an op of a worker of your own (`serve({ op(args, ctx) { ... } })`). */
  request<T = unknown>(op: string, args?: Record<string, unknown>, transfer?: Transferable[]): Promise<T>;
  /** Stops the worker; pending calls reject with a `LanepfStateError`. */
  terminate(): void;
  [Symbol.dispose](): void;
}
