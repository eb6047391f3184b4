// @ts-check
// The teaching panel: the chosen tracker's paper in a few sentences, sliders for the parameters
// the paper names, the seed, and a button back to the defaults. It calls `onChange(options,
// seed)` when the person lets go of a slider.
import { byId } from './dom.js';
import { TRACKERS, getPath, setPath } from './explain.js';

export class ParamsPanel {
  constructor(doc = document) {
    this.doc = doc;
    this.section = byId('teach', HTMLElement, doc);
    this.title = byId('teach-title', HTMLElement, doc);
    this.text = byId('teach-text', HTMLElement, doc);
    this.form = byId('params', HTMLFormElement, doc);
    this.seed = byId('seed', HTMLInputElement, doc);
    this.reset = byId('params-reset', HTMLButtonElement, doc);
    /** @type {(options: Record<string, unknown>, seed: number) => void} */
    this.onChange = () => {};
    /** The tracker shown (null: none) and the one whose options are kept. */
    /** @type {string | null} */
    this.id = null;
    /** @type {string | null} */
    this.defaultsId = null;
    /** @type {Record<string, unknown> | null} */
    this.defaults = {};
    /** @type {Record<string, unknown>} */
    this.options = {};
    this.form.addEventListener('submit', (e) => e.preventDefault());
    this.seed.addEventListener('change', () => this.changed());
    this.reset.addEventListener('click', () => {
      this.options = {};
      this.show(this.id, this.defaults);
      this.changed();
    });
  }

  /** The options that differ from the defaults (what the tracker is built with). */
  changedOptions() {
    return this.options;
  }

  seedValue() {
    const v = Number(this.seed.value);
    return Number.isSafeInteger(v) && v >= 0 ? v : 1;
  }

  changed() {
    this.onChange(this.options, this.seedValue());
  }

  /**
   * Shows tracker `id` (null: none) with its `defaults` (trackerDefaults(id)); with no defaults
   * yet (the module still loading) the sliders are there but disabled, so the page does not move
   * when they come.
   * @param {string | null} id
   * @param {Record<string, unknown> | null} defaults
   */
  show(id, defaults) {
    this.id = id;
    const info = id ? TRACKERS[id] : null;
    this.section.hidden = !info;
    if (!info) return;
    if (this.defaultsId !== id) {
      this.defaultsId = id;
      this.options = {};
    }
    this.defaults = defaults;
    this.title.textContent = info.title;
    this.text.replaceChildren(...info.text.map((t) => Object.assign(this.doc.createElement('p'), { textContent: t })));
    const current = defaults ? { ...defaults, ...this.options } : null;
    this.form.replaceChildren(...info.params.map((p) => this.control(p, current)));
  }

  /**
   * A slider or checkbox for parameter `p`, at its value in `current` (null: disabled).
   * @param {import('./explain.js').Param} p
   * @param {Record<string, unknown> | null} current
   */
  control(p, current) {
    const label = this.doc.createElement('label');
    const name = this.doc.createElement('span');
    name.textContent = p.label;
    const input = this.doc.createElement('input');
    input.name = p.path;
    input.disabled = !current;
    const value = current ? getPath(current, p.path) : p.min;
    const out = this.doc.createElement('output');
    if (p.kind === 'bool') {
      input.type = 'checkbox';
      input.checked = !!value;
      input.addEventListener('change', () => {
        this.options = setPath({ ...this.defaults, ...this.options }, p.path, input.checked);
        this.options = this.trim(this.options);
        this.changed();
      });
      label.append(input, name);
      return label;
    }
    input.type = 'range';
    Object.assign(input, { min: p.min, max: p.max, step: p.step });
    input.value = `${value}`;
    out.textContent = current ? `${value}` : '…';
    input.addEventListener('input', () => { out.textContent = input.value; });
    input.addEventListener('change', () => {
      this.options = this.trim(setPath({ ...this.defaults, ...this.options }, p.path, Number(input.value)));
      this.changed();
    });
    label.append(name, input, out);
    return label;
  }

  /**
   * Keeps only the top-level options that differ from the defaults.
   * @param {Record<string, unknown>} options
   */
  trim(options) {
    /** @type {Record<string, unknown>} */
    const out = {};
    for (const [k, v] of Object.entries(options)) {
      if (JSON.stringify(v) !== JSON.stringify(this.defaults?.[k])) out[k] = v;
    }
    return out;
  }
}
