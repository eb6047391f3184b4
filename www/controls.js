// The controls: play/pause, single step, tracker list and overlay toggles.

export class Controls {
  constructor(doc = document) {
    this.play = doc.getElementById('play');
    this.step = doc.getElementById('step');
    this.tracker = doc.getElementById('tracker');
    this.source = doc.getElementById('source');
    this.showTruth = doc.getElementById('show-truth');
    this.showCues = doc.getElementById('show-cues');
    this.status = doc.getElementById('status');
    this.timing = doc.getElementById('timing');
    this.version = doc.getElementById('version');
    this.paused = false;
    this.onStep = () => {};
    this.onSource = () => {};
    this.onTracker = () => {};
    this.tracker.addEventListener('change', () => this.onTracker(this.tracker.value));
    this.source.addEventListener('change', () => this.onSource(this.source.value));
    this.play.addEventListener('click', () => this.setPaused(!this.paused));
    this.step.addEventListener('click', () => this.onStep());
  }

  setPaused(paused) {
    this.paused = paused;
    this.play.textContent = paused ? 'Play' : 'Pause';
    this.step.disabled = !paused;
  }

  /** Fills the tracker list; while no tracker exists it says so. */
  setTrackers(ids) {
    this.tracker.replaceChildren();
    if (ids.length === 0) {
      const o = new Option('no tracker built yet', '');
      this.tracker.add(o);
      this.tracker.disabled = true;
      return;
    }
    this.tracker.add(new Option('no tracker (ground truth only)', ''));
    for (const id of ids) this.tracker.add(new Option(id, id));
    this.tracker.disabled = false;
  }

  /** Adds the simulator's scenarios after the test road. */
  setScenarios(list) {
    for (const { name, description } of list) {
      const o = new Option(`Scene: ${name}`, name);
      o.title = description;
      this.source.add(o);
    }
  }

  say(text, isError = false) {
    this.status.textContent = text;
    document.body.dataset.state = isError ? 'error' : document.body.dataset.state;
  }
}
