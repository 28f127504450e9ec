// The Dataset tab: a dataset spec (docs/datasets.md) opened from the output folder's datasets/
// or pasted and edited here, checked by the server (its error shown with the field and line),
// samples previewed as pictures (RGB, organ classes, organ and plant instances, depth) with
// what each sample holds, and a local run of its samples into a folder under the output
// folder, with progress and cancel (builder/API.md, "Datasets").
import { api } from './api.js';
import { h, render, field, numberInput, checkbox, select, toast, fmt } from './ui.js';

const POLL_MS = 250;
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/** The pictures of a preview, in the order shown, with their captions. */
export const PREVIEW_PICTURES = [
  ['rgb', 'RGB'],
  ['semantic', 'Organs'],
  ['instances', 'Organ instances'],
  ['plants', 'Plants'],
  ['depth', 'Depth'],
];

/** A starting spec: one species, one plant or a row, small pictures. */
export const STARTER_SPEC = `{
  "plantarch_dataset": 1,
  "name": "beans",
  "seed": 1,
  "samples": 10,
  "scene": {
    "species": [{"species": "bean", "age": [15, 30]}],
    "layouts": [
      {"layout": "single"},
      {"layout": "rows", "rows": 1, "plants_per_row": [2, 4], "plant_spacing": [0.15, 0.25]}
    ],
    "mesh_detail": 0.5
  },
  "camera": {"kind": "orbit", "width": 256, "height": 192, "samples_per_pixel": 1},
  "points": {"count": 5000}
}
`;

/** "12 / 100 samples · 35 per min · 0:40 left" for a run's state. */
export function runText(run) {
  const parts = [`${fmt(run.done, 0)} / ${fmt(run.total, 0)} samples`];
  if (run.per_minute > 0) parts.push(`${fmt(run.per_minute, 1)} per min`);
  if (run.state === 'running' && Number.isFinite(run.seconds_left)) {
    const s = Math.round(run.seconds_left);
    const two = (n) => String(n).padStart(2, '0');
    const clock =
      s >= 3600
        ? `${Math.floor(s / 3600)}:${two(Math.floor(s / 60) % 60)}:${two(s % 60)}`
        : `${Math.floor(s / 60)}:${two(s % 60)}`;
    parts.push(`${clock} left`);
  }
  if (run.state === 'done') parts.push(`${fmt(run.bytes / 1e6, 1)} MB in ${fmt(run.seconds, 1)} s`);
  if (run.state === 'cancelled') parts.push('cancelled');
  return parts.join(' · ');
}

export class DatasetPanel {
  constructor(app, container) {
    this.app = app;
    this.container = container;
    this.text = STARTER_SPEC;
    this.specs = null; // spec files under the output folder, once listed
    this.checked = null; // the server's summary of the text checked, or null
    this.error = null; // {error, field, line} of the last check
    this.first = 0;
    this.count = 3;
    this.previews = [];
    this.previewing = false;
    this.out = '';
    this.samples = null;
    this.resume = false;
    this.run = null; // the run shown: the server's state
    this.built = false;
  }

  /** Builds the tab's elements once; later calls refresh what changes. */
  render() {
    if (!this.built) this.build();
    this.refreshSpecs();
  }

  build() {
    this.built = true;
    this.editor = h('textarea', {
      id: 'dataset-spec',
      rows: 11,
      spellcheck: false,
      value: this.text,
    });
    this.editor.addEventListener('input', () => {
      this.text = this.editor.value;
      this.checked = null;
      this.editor.classList.remove('invalid');
      this.showCheck({ stale: true });
    });
    this.specSelect = h('select', { id: 'dataset-file', name: 'dataset-file' });
    this.checkStatus = h('div', { id: 'dataset-check', class: 'dataset-check' });
    this.strip = h('div', { id: 'dataset-previews', class: 'dataset-previews' });
    this.previewButton = h(
      'button',
      { type: 'button', id: 'dataset-preview', onclick: () => this.preview() },
      'Preview',
    );
    this.outInput = h('input', {
      type: 'text',
      name: 'dataset-out',
      placeholder: 'datasets/NAME',
      value: this.out,
    });
    this.outInput.addEventListener('input', () => {
      this.out = this.outInput.value;
    });
    this.samplesInput = numberInput(
      this.samples ?? '',
      (v) => {
        this.samples = v;
      },
      { min: 1, max: 10000000, integer: true, name: 'dataset-samples' },
    );
    this.samplesInput.placeholder = 'the spec’s';
    this.runButton = h(
      'button',
      { type: 'button', class: 'primary', id: 'dataset-run', onclick: () => this.start() },
      'Run',
    );
    this.cancelButton = h(
      'button',
      { type: 'button', id: 'dataset-cancel', disabled: true, onclick: () => this.cancel() },
      'Cancel',
    );
    this.runFill = h('div', { class: 'progress-fill' });
    this.runLine = h('span', { class: 'progress-text' }, 'No run yet');
    this.runStatus = h(
      'div',
      {
        class: 'build-status dataset-run-status',
        id: 'dataset-run-status',
        dataset: { state: 'idle' },
      },
      h('div', { class: 'progress' }, this.runFill),
      this.runLine,
    );
    this.runResult = h('div', { class: 'dataset-run-result', id: 'dataset-run-result' });

    render(
      this.container,
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Dataset spec'),
        h(
          'p',
          { class: 'hint' },
          'A spec from the output folder’s ',
          h('code', {}, 'datasets/'),
          ', or written here (docs/datasets.md). Relative species files are taken from ',
          h('code', {}, 'datasets/'),
          '.',
        ),
        h(
          'div',
          { class: 'dataset-open' },
          this.specSelect,
          h(
            'button',
            { type: 'button', id: 'dataset-open', onclick: () => this.open() },
            'Open',
          ),
          h(
            'button',
            {
              type: 'button',
              title: 'A small spec to start from',
              onclick: () => this.setText(STARTER_SPEC),
            },
            'Starter',
          ),
        ),
        this.editor,
        h(
          'div',
          { class: 'dataset-actions' },
          h(
            'button',
            { type: 'button', id: 'dataset-check-button', onclick: () => this.check() },
            'Check',
          ),
          this.checkStatus,
        ),
      ),
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Preview'),
        h(
          'div',
          { class: 'dataset-actions' },
          field(
            'First sample',
            numberInput(
              this.first,
              (v) => {
                this.first = v;
              },
              { min: 0, max: 9999999, integer: true, name: 'dataset-first' },
            ),
          ),
          field(
            'Samples',
            select(
              [1, 2, 3, 4, 6, 8].map((n) => [String(n), String(n)]),
              String(this.count),
              (v) => {
                this.count = Number(v);
              },
              { name: 'dataset-count' },
            ),
          ),
          this.previewButton,
        ),
        this.strip,
      ),
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Run'),
        h(
          'p',
          { class: 'hint' },
          'Every sample’s files, the manifest, ',
          h('code', {}, 'dataset.json'),
          ' and the per-split COCO files, written into a folder under the output folder',
          this.app.config?.output ? [' (', h('code', {}, this.app.config.output), ')'] : null,
          ', as ',
          h('code', {}, 'plantarch dataset SPEC --out DIR'),
          ' writes them.',
        ),
        h(
          'div',
          { class: 'grid2' },
          field('Folder', this.outInput, { title: 'a folder under the output folder' }),
          field('Samples', this.samplesInput, { title: 'default: the spec’s samples' }),
        ),
        h(
          'label',
          { class: 'toggle', title: 'keep the samples the folder holds and make the others' },
          checkbox(
            this.resume,
            (v) => {
              this.resume = v;
            },
            { name: 'dataset-resume' },
          ),
          'Resume',
        ),
        h('div', { class: 'dataset-actions' }, this.runButton, this.cancelButton),
        this.runStatus,
        this.runResult,
      ),
    );
    this.showCheck();
  }

  setText(text) {
    this.text = text;
    this.editor.value = text;
    this.editor.dispatchEvent(new Event('input'));
  }

  async refreshSpecs() {
    try {
      this.specs = await api.datasetSpecs();
    } catch {
      this.specs = [];
    }
    const chosen = this.specSelect.value;
    render(
      this.specSelect,
      this.specs.length
        ? this.specs.map((p) => h('option', { value: p, selected: p === chosen }, p))
        : h('option', { value: '' }, 'no spec in datasets/'),
    );
    this.specSelect.disabled = !this.specs.length;
  }

  async open() {
    const path = this.specSelect.value;
    if (!path) return;
    try {
      const { text } = await api.datasetSpec(path);
      this.setText(text);
      await this.check();
    } catch (e) {
      toast(e.message, 'error');
    }
  }

  /** Asks the server to check the text; shows its summary or its error. */
  async check() {
    this.checkStatus.dataset.state = 'checking';
    render(this.checkStatus, h('span', { class: 'hint' }, 'Checking…'));
    try {
      this.checked = await api.checkDataset({ text: this.text });
      this.error = null;
      if (!this.out) {
        this.out = `datasets/${this.checked.name.replace(/[^A-Za-z0-9_.-]+/g, '_')}`;
        this.outInput.value = this.out;
      }
    } catch (e) {
      this.checked = null;
      this.error = { error: e.message, field: e.data?.field, line: e.data?.line };
    }
    this.showCheck();
    return this.checked;
  }

  showCheck({ stale } = {}) {
    const s = this.checked;
    this.editor.classList.toggle('invalid', !!this.error && !stale);
    if (stale) {
      this.error = null;
      this.checkStatus.dataset.state = 'stale';
      render(this.checkStatus, h('span', { class: 'hint' }, 'Edited: check it again.'));
    } else if (this.error) {
      this.checkStatus.dataset.state = 'error';
      render(
        this.checkStatus,
        h('p', { class: 'error-text' }, this.error.error),
        // The field, when the line does not name it already.
        this.error.field && !this.error.error.includes(this.error.field)
          ? h('p', { class: 'hint' }, 'Field: ', h('code', {}, this.error.field))
          : null,
      );
      if (this.error.line) this.selectLine(this.error.line);
    } else if (s) {
      this.checkStatus.dataset.state = 'valid';
      const splits = s.splits.map((x) => `${x.name} ${fmt(100 * x.fraction, 1)}%`).join(', ');
      render(
        this.checkStatus,
        h(
          'p',
          { class: 'dataset-summary' },
          h('strong', {}, s.name),
          `: ${fmt(s.samples, 0)} samples of ${s.image[0]} × ${s.image[1]} px; `,
          s.species.join(', '),
          s.weeds.length ? ` with weeds (${s.weeds.join(', ')})` : '',
          '; ',
          `splits ${splits}.`,
        ),
      );
    } else {
      this.checkStatus.dataset.state = 'idle';
      render(this.checkStatus, h('span', { class: 'hint' }, 'Not checked yet.'));
    }
  }

  // Selects line `n` (1-based) of the editor, where the reader found the error.
  selectLine(n) {
    const lines = this.text.split('\n');
    if (n < 1 || n > lines.length) return;
    const start = lines.slice(0, n - 1).reduce((a, l) => a + l.length + 1, 0);
    this.editor.setSelectionRange(start, start + lines[n - 1].length);
  }

  /** Previews samples first .. first + count - 1, one after the other. */
  async preview() {
    if (this.previewing) return;
    if (!(await this.check())) return;
    this.previewing = true;
    this.previewButton.disabled = true;
    this.strip.dataset.state = 'loading';
    render(this.strip);
    try {
      for (let i = this.first; i < this.first + this.count; i++) {
        const card = h(
          'div',
          { class: 'dataset-sample loading' },
          h('p', { class: 'hint' }, `Sample ${i}…`),
        );
        this.strip.append(card);
        try {
          const p = await api.previewDataset({ text: this.text, sample: i });
          this.showSample(card, p);
        } catch (e) {
          card.classList.remove('loading');
          render(card, h('p', { class: 'error-text' }, `Sample ${i}: ${e.message}`));
          throw e;
        }
      }
      this.strip.dataset.state = 'done';
    } catch {
      this.strip.dataset.state = 'error';
    } finally {
      this.previewing = false;
      this.previewButton.disabled = false;
    }
  }

  showSample(card, p) {
    const s = p.summary;
    const species = Object.entries(s.plants_by_species)
      .map(([name, n]) => `${n} ${name}`)
      .join(', ');
    card.classList.remove('loading');
    card.dataset.sample = s.sample;
    render(
      card,
      h(
        'p',
        { class: 'dataset-sample-head' },
        h('strong', {}, `Sample ${s.sample}`),
        h('span', { class: `split split-${s.split}` }, s.split),
        ` ${species}; ${fmt(s.annotations, 0)} annotations;`,
        ` day ${fmt(s.day_of_year, 0)}, ${fmt(s.solar_hour, 1)} h`,
      ),
      h(
        'div',
        { class: 'dataset-pictures' },
        PREVIEW_PICTURES.map(([key, caption]) =>
          h(
            'figure',
            {},
            h(
              'a',
              { href: p.images[key], target: '_blank', rel: 'noopener' },
              h('img', {
                src: p.images[key],
                alt: `sample ${s.sample}: ${caption}`,
                dataset: { picture: key },
              }),
            ),
            h('figcaption', {}, caption),
          ),
        ),
      ),
    );
  }

  /** Starts a run of the checked spec; polls it until it stops. */
  async start() {
    if (this.run?.state === 'running') return;
    render(this.runResult);
    if (!(await this.check())) {
      render(this.runResult, h('p', { class: 'error-text' }, 'Mend the spec first.'));
      return;
    }
    const body = { text: this.text, out: this.out.trim(), resume: this.resume };
    if (this.samples) body.samples = this.samples;
    let id;
    try {
      ({ id } = await api.startDatasetRun(body));
    } catch (e) {
      render(this.runResult, h('p', { class: 'error-text' }, e.message));
      return;
    }
    this.runButton.disabled = true;
    this.cancelButton.disabled = false;
    this.runStatus.dataset.run = id;
    for (;;) {
      try {
        this.run = await api.datasetRun(id);
      } catch (e) {
        this.run = { id, state: 'failed', error: e.message, done: 0, total: 0 };
      }
      this.showRun();
      if (this.run.state !== 'running') break;
      await sleep(POLL_MS);
    }
    this.runButton.disabled = false;
    this.cancelButton.disabled = true;
    if (this.run.state === 'done') toast(`Dataset written into ${this.run.out}`);
  }

  showRun() {
    const r = this.run;
    this.runStatus.dataset.state = r.state;
    this.runFill.style.width = `${Math.round(100 * (r.total ? r.done / r.total : 0))}%`;
    this.runLine.textContent = r.state === 'failed' ? 'failed' : runText(r);
    if (r.state === 'failed') render(this.runResult, h('p', { class: 'error-text' }, r.error));
    else if (r.state === 'done')
      render(
        this.runResult,
        h(
          'p',
          { class: 'hint' },
          'Written: ',
          h('code', {}, `${r.out}/dataset.json`),
          ', ',
          h('code', {}, `${r.out}/samples/`),
          '.',
        ),
      );
    else if (r.state === 'cancelled')
      render(
        this.runResult,
        h(
          'p',
          { class: 'hint' },
          `Stopped: ${r.done} whole samples kept in `,
          h('code', {}, r.out),
          ' (Resume goes on).',
        ),
      );
  }

  async cancel() {
    if (!this.run?.id && !this.runStatus.dataset.run) return;
    try {
      await api.cancelDatasetRun(this.runStatus.dataset.run);
    } catch (e) {
      toast(e.message, 'error');
    }
  }
}
