// Talks to the tracking worker (worker.js) with request/response promises.
// Every request carries an id; the worker answers { id, ok, result } or
// { id, ok: false, error, name } (the message and the error's kind).

export class WorkerClient {
  constructor(url = new URL('./worker.js', import.meta.url)) {
    this.worker = new Worker(url, { type: 'module' });
    this.pending = new Map();
    this.nextId = 1;
    this.worker.onmessage = (e) => {
      const { id, ok, result, error, name, rgba } = e.data;
      const p = this.pending.get(id);
      if (!p) return;
      this.pending.delete(id);
      // A failed request keeps the error's kind in `err.name` and hands transferred pixels back
      // on the Error (`err.rgba`).
      ok ? p.resolve(result) : p.reject(Object.assign(new Error(error), { rgba }, name ? { name } : {}));
    };
    this.worker.onerror = (e) => {
      const err = new Error(`worker failed: ${e.message ?? 'unknown error'}`);
      for (const p of this.pending.values()) p.reject(err);
      this.pending.clear();
    };
  }

  /** Sends `{ type, ...payload }`; resolves with the worker's result. */
  request(type, payload = {}, transfer = []) {
    if ('id' in payload || 'type' in payload) {
      return Promise.reject(new Error(`request '${type}': payload keys 'id' and 'type' are reserved`));
    }
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ id, type, ...payload }, transfer);
    });
  }

  terminate() {
    this.worker.terminate();
  }
}
