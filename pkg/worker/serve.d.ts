// `lanepf/worker/serve.js`: the request loop of TrackerWorker's module worker, for a worker of
// your own that adds ops next to the tracker's.
import type * as lanepf from '../web/lanepf.js';

/** What an op gets besides its arguments. */
export interface ServeContext {
  /** The package module, initialised. */
  lanepf: typeof lanepf;
  /** The tracker `TrackerWorker.create` / `open` built, or null. */
  readonly tracker: lanepf.Tracker | null;
}

/** An op's answer: the result, and the buffers to transfer with it. */
export interface OpResult {
  result?: unknown;
  transfer?: Transferable[];
}

/** An op of your own: called with the request's `args`. */
export type Op = (args: any, ctx: ServeContext) => OpResult | void | Promise<OpResult | void>;

/**
 * Answers TrackerWorker's requests in this worker: the tracker's ops and `extra` (names must
 * not be the tracker's own: version, open, step, track, beginFrame, advance, nextStep, reset, particles,
 * hypotheses, layers, resamplings, close).
 */
export function serve(extra?: Record<string, Op>): void;
