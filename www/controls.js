// @ts-check
// The controls: source, tracker and camera pickers, playback, teaching steps, overlay toggles,
// export. They hold no tracking state; main.js reacts to their callbacks.

import { byId } from './dom.js';

export class Controls {
  constructor(doc = document) {
    /** @param {string} id */
    const button = (id) => byId(id, HTMLButtonElement, doc);
    /** @param {string} id */
    const input = (id) => byId(id, HTMLInputElement, doc);
    /** @param {string} id */
    const select = (id) => byId(id, HTMLSelectElement, doc);
    /** @param {string} id */
    const element = (id) => byId(id, HTMLElement, doc);
    this.play = button('play');
    this.step = button('step');
    this.stepStage = button('step-stage');
    this.nextStage = element('next-stage');
    this.restart = button('restart');
    this.progress = byId('progress', HTMLProgressElement, doc);
    this.tracker = select('tracker');
    this.source = select('source');
    this.file = input('file');
    this.cameraFile = input('camera-file');
    this.showTruth = input('show-truth');
    this.showParticles = input('show-particles');
    this.showTop = input('show-top');
    this.showCues = input('show-cues');
    this.showPlots = input('show-plots');
    this.departure = element('departure');
    this.cueLayer = select('cue-layer');
    this.colourGroups = input('colour-groups');
    this.stereo = input('stereo');
    this.compare = select('compare');
    this.exportJsonl = button('export-jsonl');
    this.exportCsv = button('export-csv');
    this.status = element('status');
    this.timing = element('timing');
    this.version = element('version');
    this.dropZone = element('drop-zone');
    this.paused = false;
    /** @type {string[]} */
    this.stepNames = [];
    // The callbacks main.js sets.
    /** @type {() => void} */
    this.onStep = () => {};
    /** @type {() => void} */
    this.onStepStage = () => {};
    /** @type {() => void} */
    this.onRestart = () => {};
    /** @type {(value: string) => void} */
    this.onSource = () => {};
    /** @type {(files: File[]) => void} */
    this.onFiles = () => {};
    /** @type {(file: File) => void} */
    this.onCameraFile = () => {};
    /** @type {(id: string) => void} */
    this.onTracker = () => {};
    /** @type {(id: string) => void} */
    this.onCompare = () => {};
    /** @type {(format: 'jsonl' | 'csv') => void} */
    this.onExport = () => {};
    this.lastSource = this.source.value;
    this.tracker.addEventListener('change', () => this.onTracker(this.tracker.value));
    this.compare.addEventListener('change', () => this.onCompare(this.compare.value));
    this.source.addEventListener('change', () => {
      if (this.source.value === 'file') {
        // Picking files is its own step; until then the old source stays selected.
        this.source.value = this.lastSource;
        this.file.click();
        return;
      }
      this.lastSource = this.source.value;
      this.onSource(this.source.value);
    });
    this.file.addEventListener('change', () => {
      const files = this.file.files;
      if (files?.length) this.onFiles([...files]);
      this.file.value = '';
    });
    this.cameraFile.addEventListener('change', () => {
      const file = this.cameraFile.files?.[0];
      if (file) this.onCameraFile(file);
    });
    this.play.addEventListener('click', () => this.setPaused(!this.paused));
    this.step.addEventListener('click', () => this.onStep());
    this.stepStage.addEventListener('click', () => this.onStepStage());
    this.restart.addEventListener('click', () => this.onRestart());
    this.exportJsonl.addEventListener('click', () => this.onExport('jsonl'));
    this.exportCsv.addEventListener('click', () => this.onExport('csv'));
    // Drag and drop of videos or images onto the views.
    this.dropZone.addEventListener('dragover', (e) => {
      e.preventDefault();
      this.dropZone.classList.add('dropping');
    });
    this.dropZone.addEventListener('dragleave', () => this.dropZone.classList.remove('dropping'));
    this.dropZone.addEventListener('drop', (e) => {
      e.preventDefault();
      this.dropZone.classList.remove('dropping');
      if (e.dataTransfer?.files.length) this.onFiles([...e.dataTransfer.files]);
    });
    // Keyboard: space plays or pauses, "." steps a frame, "," steps a stage.
    doc.addEventListener('keydown', (e) => {
      // (Not while a control has the focus: space there is that control's own key.)
      if ((e.target instanceof Element && e.target.closest('input, select, textarea, button, summary')) || e.ctrlKey || e.metaKey || e.altKey) return;
      if (e.key === ' ') {
        e.preventDefault();
        this.setPaused(!this.paused);
      } else if (e.key === '.' && !this.step.disabled) {
        this.onStep();
      } else if (e.key === ',' && !this.stepStage.disabled) {
        this.onStepStage();
      }
    });
  }

  /** @param {boolean} paused */
  setPaused(paused) {
    this.paused = paused;
    this.play.textContent = paused ? 'Play' : 'Pause';
    this.step.disabled = !paused;
    this.updateStageButton();
  }

  /**
   * The per-step button works while paused, for a tracker with a per-step mode.
   * @param {string[] | null | undefined} names
   */
  setStepNames(names) {
    this.stepNames = names ?? [];
    this.updateStageButton();
  }

  /** @param {number | null} [next] the index in `stepNames` of the next step (null: a frame's start) */
  updateStageButton(next = null) {
    const can = this.paused && this.stepNames?.length > 0;
    this.stepStage.disabled = !can;
    if (!this.stepNames?.length) {
      this.nextStage.textContent = '';
    } else {
      const name = next === null ? 'start of a frame (read the image, compute its cues)' : this.stepNames[next];
      this.nextStage.textContent = `next: ${name}`;
    }
  }

  /**
   * The "Ground truth" control is shown only for a source that has ground truth (the simulator's).
   * @param {boolean} yes
   */
  setHasTruth(yes) {
    const label = this.showTruth.closest('label');
    if (label) label.hidden = !yes;
  }

  /**
   * Shows progress in [0, 1], or hides the bar for a source without an end (null).
   * @param {number | null} value
   */
  setProgress(value) {
    const known = typeof value === 'number' && value >= 0;
    this.progress.hidden = !known;
    if (known) this.progress.value = value;
  }

  /** @param {boolean} yes */
  setExportable(yes) {
    this.exportJsonl.disabled = !yes;
    this.exportCsv.disabled = !yes;
  }

  /**
   * Lists the tracker's cue layers by name, keeping the choice when the names stay.
   * @param {{ name: string }[] | null | undefined} layers
   */
  setLayers(layers) {
    const names = (layers ?? []).map((l) => l.name);
    const old = [...this.cueLayer.options].map((o) => o.textContent);
    if (names.join('\n') !== old.join('\n')) {
      const chosen = this.cueLayer.value;
      this.cueLayer.replaceChildren(...names.map((n, k) => new Option(n, `${k}`)));
      if (chosen !== '' && Number(chosen) < names.length) this.cueLayer.value = chosen;
    }
    this.cueLayer.hidden = names.length < 2;
    return Number(this.cueLayer.value) || 0;
  }

  /**
   * The tracker lists: "no tracker" (or "nothing" to compare with) and then every registered id.
   * index.html lists them already, so the menus work while the module loads; they are rebuilt
   * only if the module's list differs, keeping the choice.
   * @param {string[]} ids
   */
  setTrackers(ids) {
    /**
     * @param {HTMLSelectElement} select
     * @param {string} none the label of the empty choice
     */
    const fill = (select, none) => {
      const have = [...select.options].map((o) => o.value);
      if (have.join('\n') === ['', ...ids].join('\n')) return;
      const chosen = select.value;
      select.replaceChildren(new Option(none, ''), ...ids.map((id) => new Option(id, id)));
      select.value = ids.includes(chosen) ? chosen : '';
    };
    fill(this.tracker, 'no tracker (frames only)');
    fill(this.compare, 'nothing');
  }

  /**
   * Adds the simulator's scenarios after the built-in sources.
   * @param {{ name: string, description: string }[]} list
   */
  setScenarios(list) {
    for (const { name, description } of list) {
      const o = new Option(`Scene: ${name}`, name);
      o.title = description;
      this.source.add(o);
    }
  }

  /**
   * Selects a source option, adding it (e.g. an uploaded file's name) when missing.
   * @param {string} value
   * @param {string} label
   */
  showSource(value, label) {
    if (![...this.source.options].some((o) => o.value === value)) {
      this.source.add(new Option(label, value), this.source.options[3]);
    }
    this.source.value = value;
    this.lastSource = value;
  }

  /**
   * The status line; `isError` marks the page as in error (the tests wait on it).
   * @param {string} text
   * @param {boolean} [isError]
   */
  say(text, isError = false) {
    this.status.textContent = text;
    if (isError) document.body.dataset.state = 'error';
    else if (document.body.dataset.state === 'error') document.body.dataset.state = 'running';
  }
}
