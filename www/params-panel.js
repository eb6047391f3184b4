// @ts-check
// The teaching panel: the chosen tracker's paper in a few sentences, sliders for the parameters
// the paper names, the seed, and two presets: the paper's defaults, and our options beyond the
// papers for real footage (`trackerPreset(id, 'real-roads')`), which the page picks for the
// clip, your media and the webcam, and the paper's for the simulator. It calls
// `onChange(options, seed)` when the person lets go of a slider or picks a preset.
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
    this.realRoadsButton = byId('params-real-roads', HTMLButtonElement, doc);
    this.presetText = byId('params-preset', HTMLElement, doc);
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
    /** The preset the options start from. @type {'paper' | 'real-roads'} */
    this.preset = 'paper';
    /** The shown tracker's real-roads options. @type {Record<string, unknown> | null} */
    this.realRoads = null;
    this.form.addEventListener('submit', (e) => e.preventDefault());
    this.seed.addEventListener('change', () => this.changed());
    this.reset.addEventListener('click', () => {
      this.usePreset('paper');
      this.show(this.id, this.defaults, this.realRoads);
      this.changed();
    });
    this.realRoadsButton.addEventListener('click', () => {
      this.usePreset('real-roads');
      this.show(this.id, this.defaults, this.realRoads);
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
   * Starts the options afresh from `preset` when the panel next shows a tracker: the person's
   * own changes are dropped.
   * @param {'paper' | 'real-roads'} preset
   */
  usePreset(preset) {
    this.preset = preset;
    this.defaultsId = null;
  }

  /**
   * Shows tracker `id` (null: none) with its `defaults` (trackerDefaults(id)) and its
   * `realRoads` options (trackerPreset(id, 'real-roads')); with no defaults yet (the module
   * still loading) the sliders are there but disabled, so the page does not move when they
   * come. A new tracker starts from the current preset.
   * @param {string | null} id
   * @param {Record<string, unknown> | null} defaults
   * @param {Record<string, unknown> | null} [realRoads]
   */
  show(id, defaults, realRoads = null) {
    this.id = id;
    const info = id ? TRACKERS[id] : null;
    this.section.hidden = !info;
    if (!info) return;
    this.defaults = defaults;
    this.realRoads = realRoads;
    if (this.defaultsId !== id && defaults) {
      this.defaultsId = id;
      this.options = this.preset === 'real-roads' && realRoads ? this.trim(realRoads) : {};
    }
    const ours = Object.keys(this.trim(realRoads ?? {}));
    this.presetText.textContent = this.preset === 'paper' ? 'Options: the paper’s filter, then your changes.'
      : ours.length ? `Options: real roads (ours, beyond the paper: ${ours.join(', ')}), then your changes.`
        : 'Options: real roads, which for this tracker is the paper’s filter (none of our options measured better), then your changes.';
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
