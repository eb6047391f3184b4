// @ts-check
// Windowed reads of a Blob (a File, or a fetched clip): the demuxers walk a container's
// headers and the WebCodecs source reads sample data by offset, one window (1 MiB by default)
// at a time, so a big video is never held in memory whole.

/** The error for bytes asked beyond the end of the file. */
export class TruncatedError extends Error {}

export class BlobReader {
  /**
   * @param {Blob} blob
   * @param {number} [window] bytes loaded at a time
   */
  constructor(blob, window = 1 << 20) {
    this.blob = blob;
    this.size = blob.size;
    this.window = window;
    this.start = 0;
    this.bytes = new Uint8Array(0);
  }

  /**
   * Whether [pos, pos + n) is in the loaded window.
   * @param {number} pos
   * @param {number} n
   */
  has(pos, n) {
    return pos >= this.start && pos + n <= this.start + this.bytes.length;
  }

  /**
   * Loads a window from `pos` holding at least `n` bytes (fewer at the end of the file).
   * @param {number} pos
   * @param {number} n
   */
  async load(pos, n) {
    const end = Math.min(this.size, pos + Math.max(n, this.window));
    this.bytes = new Uint8Array(await this.blob.slice(pos, end).arrayBuffer());
    this.start = pos;
  }

  /**
   * The `n` bytes at `pos` (a view into the window, valid until the next read).
   * @param {number} pos
   * @param {number} n
   * @param {string} [what] what the bytes are, for the error
   */
  async read(pos, n, what = 'data') {
    if (pos + n > this.size) {
      throw new TruncatedError(`the file is truncated: ${what} at byte ${pos} needs ${n} bytes, `
        + `but the file ends at byte ${this.size}`);
    }
    if (!this.has(pos, n)) await this.load(pos, n);
    return this.bytes.subarray(pos - this.start, pos - this.start + n);
  }

  /**
   * Up to `n` bytes at `pos`, fewer at the end of the file (for headers of unknown length).
   * @param {number} pos
   * @param {number} n
   */
  async peek(pos, n) {
    const m = Math.max(0, Math.min(n, this.size - pos));
    if (!this.has(pos, m)) await this.load(pos, m);
    return this.bytes.subarray(pos - this.start, pos - this.start + m);
  }
}
