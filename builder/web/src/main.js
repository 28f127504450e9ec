// plantarch builder: the single-page app. Blocks of plants and the scene's environment are
// edited in the side panel; each change is built by the server (POST /api/builds), whose
// progress is shown until the scene's GLB is loaded into the 3D view.
import { api } from './api.js';
import { setDefaults } from './defaults.js';
import { defaultProject, toProjectFile, fromProjectFile } from './project.js';
import { Viewer } from './viewer.js';
import { progressText } from './physiology_panel.js';
import { COLOR_MODES, modeUnavailable, rampGradient } from './labels.js';
import { ScenePanel } from './scene_panel.js';
import { EnvironmentPanel } from './environment_panel.js';
import { SpeciesEditor } from './species_editor.js';
import { ExportPanel } from './export_panel.js';
import { DatasetPanel } from './dataset_panel.js';
import { h, render, select, toast, fmt, download, icon } from './ui.js';

const POLL_MS = 200;
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// The project without its ages: two projects with equal keys differ only by age, so the later
// one can be grown from the earlier one's build ("from"). A project with a physiology season
// is never grown on (its weather is dated): the server builds it again.
function growthKey(projectFile) {
  return JSON.stringify({
    ...projectFile,
    blocks: projectFile.blocks.map(({ age, ...rest }) => rest),
  });
}

// Decimals for the ends of a ramp spanning `span`: enough to tell them apart.
function rampDigits(span) {
  if (!(span > 0)) return 3;
  return Math.max(0, Math.min(4, 2 - Math.floor(Math.log10(span))));
}

/** "flat" or "textured:SIZE": which materials a scene.glb was asked with. */
function lookKey(look) {
  return look.materials === 'textured' ? `textured:${look.textureSize}` : 'flat';
}

class App {
  constructor(root) {
    this.project = defaultProject();
    this.species = [];
    this.details = new Map();
    this.current = null; // the build in progress: {id, state, ...}
    this.shownBuild = null; // the build in the view: {id, stats, age, key, project}
    this.autoBuild = true;
    this.playing = false;
    this.buildTimer = null;
    this.layout(root);
  }

  layout(root) {
    const tab = (id, label) =>
      h(
        'button',
        {
          type: 'button',
          class: 'tab',
          role: 'tab',
          dataset: { tab: id },
          onclick: () => this.showTab(id),
        },
        label,
      );
    this.nameInput = h('input', {
      type: 'text',
      id: 'project-name',
      value: this.project.name,
      title: 'Project name',
      spellcheck: false,
    });
    this.nameInput.addEventListener('change', () => {
      this.project.name = this.nameInput.value.trim() || 'untitled';
    });
    this.uploadInput = h('input', {
      type: 'file',
      accept: '.json,application/json',
      hidden: true,
      id: 'project-upload',
    });
    this.uploadInput.addEventListener('change', () => this.upload());

    this.panels = {
      scene: h('div', { class: 'tab-body', dataset: { panel: 'scene' } }),
      environment: h('div', { class: 'tab-body', dataset: { panel: 'environment' } }),
      species: h('div', { class: 'tab-body', dataset: { panel: 'species' } }),
      export: h('div', { class: 'tab-body', dataset: { panel: 'export' } }),
      dataset: h('div', { class: 'tab-body', dataset: { panel: 'dataset' } }),
    };
    this.scenePanel = new ScenePanel(this, this.panels.scene);
    this.environmentPanel = new EnvironmentPanel(this, this.panels.environment);
    this.speciesEditor = new SpeciesEditor(this, this.panels.species);
    this.exportPanel = new ExportPanel(this, this.panels.export);
    this.datasetPanel = new DatasetPanel(this, this.panels.dataset);

    this.viewport = h('div', {
      class: 'viewport',
      id: 'viewport',
      dataset: { look: 'flat' },
    });
    this.legend = h('div', { class: 'legend', hidden: true, id: 'legend' });
    this.pickInfo = h('div', { class: 'pick-info', hidden: true });
    this.emptyState = h(
      'div',
      { class: 'empty-state' },
      h('p', {}, 'Build the scene to see it here.'),
    );
    this.statsPanel = h('div', { class: 'stats', id: 'stats' });
    this.previewImg = h('img', {
      id: 'preview-image',
      alt: "the scene drawn by plantarch's renderer",
    });
    this.preview = h(
      'div',
      { class: 'preview', hidden: true },
      this.previewImg,
      h('p', { class: 'preview-caption' }, "plantarch's own renderer"),
    );
    this.colorSelect = select(COLOR_MODES, 'natural', (m) => this.viewer.setMode(m), {
      id: 'color-mode',
      title: 'Colour by',
    });
    // The materials of the view and of the export (the Export tab's are the same).
    this.look = { materials: 'flat', textureSize: 512 };
    this.lookSelect = select(
      [
        ['flat', 'Flat colours'],
        ['textured', 'Textured'],
      ],
      'flat',
      (v) => this.setLook({ materials: v }),
      { id: 'view-materials', title: 'Materials of the view and of the export' },
    );

    this.buildButton = h(
      'button',
      { type: 'button', class: 'primary', id: 'build', onclick: () => this.build() },
      'Build',
    );
    this.cancelButton = h(
      'button',
      { type: 'button', id: 'cancel', disabled: true, onclick: () => this.cancel() },
      'Cancel',
    );
    this.progressBar = h('div', { class: 'progress-fill' });
    this.progressText = h('span', { class: 'progress-text' }, 'Ready');
    this.buildStatus = h(
      'div',
      { class: 'build-status', id: 'build-status', dataset: { state: 'idle' } },
      h('div', { class: 'progress' }, this.progressBar),
      this.progressText,
    );
    this.buildError = h('div', { class: 'build-error', id: 'build-error', hidden: true });
    const auto = h('input', { type: 'checkbox', id: 'auto-build', checked: true });
    auto.addEventListener('change', () => {
      this.autoBuild = auto.checked;
    });
    this.playButton = h(
      'button',
      {
        type: 'button',
        class: 'icon play',
        id: 'play',
        title: 'Grow day by day',
        onclick: () => this.togglePlay(),
      },
      icon('play'),
    );
    this.ageSlider = h('input', {
      type: 'range',
      id: 'age-slider',
      min: 0,
      max: 100,
      step: 1,
      value: 40,
    });
    this.ageLabel = h('span', { class: 'age-label', id: 'age-label' }, '40 d');
    this.ageSlider.addEventListener('input', () => {
      this.ageLabel.textContent = `${this.ageSlider.value} d`;
    });
    this.ageSlider.addEventListener('change', () => this.setSceneAge(Number(this.ageSlider.value)));

    render(
      root,
      h(
        'header',
        { class: 'topbar' },
        h(
          'div',
          { class: 'brand' },
          h('img', { src: '/favicon.svg', alt: '', width: 22, height: 22 }),
          h('span', {}, 'plantarch'),
          h('span', { class: 'brand-sub' }, 'builder'),
        ),
        h(
          'div',
          { class: 'project-controls' },
          this.nameInput,
          h(
            'button',
            {
              type: 'button',
              onclick: () => this.newProject(),
              title: 'A new project with one block',
            },
            'New',
          ),
          h(
            'button',
            { type: 'button', id: 'project-open', onclick: () => this.openDialog() },
            'Open…',
          ),
          h(
            'button',
            {
              type: 'button',
              id: 'project-save',
              onclick: () => this.saveProject(),
              title: 'Save into projects/ under the output folder',
            },
            'Save',
          ),
          h(
            'button',
            {
              type: 'button',
              id: 'project-download',
              onclick: () => this.downloadProject(),
              title: 'Download the project file (JSON)',
            },
            'Download',
          ),
          h(
            'button',
            {
              type: 'button',
              id: 'project-upload-button',
              onclick: () => this.uploadInput.click(),
              title: 'Load a project file (JSON)',
            },
            'Upload',
          ),
          this.uploadInput,
        ),
      ),
      h(
        'main',
        { class: 'layout' },
        h(
          'aside',
          { class: 'sidebar' },
          h(
            'nav',
            { class: 'tabs', role: 'tablist' },
            tab('scene', 'Scene'),
            tab('environment', 'Environment'),
            tab('species', 'Species'),
            tab('export', 'Export'),
            tab('dataset', 'Dataset'),
          ),
          Object.values(this.panels),
        ),
        h(
          'section',
          { class: 'stage' },
          h(
            'div',
            { class: 'stage-bar' },
            h(
              'div',
              { class: 'segmented', role: 'tablist' },
              h(
                'button',
                {
                  type: 'button',
                  class: 'seg active',
                  dataset: { view: '3d' },
                  id: 'show-3d',
                  onclick: () => this.showView('3d'),
                },
                '3D view',
              ),
              h(
                'button',
                {
                  type: 'button',
                  class: 'seg',
                  dataset: { view: 'preview' },
                  id: 'show-preview',
                  onclick: () => this.showView('preview'),
                },
                'Rendered preview',
              ),
            ),
            h('label', { class: 'inline' }, 'Colour by', this.colorSelect),
            h('label', { class: 'inline' }, 'Materials', this.lookSelect),
            h(
              'button',
              {
                type: 'button',
                class: 'small',
                title: 'Frame the whole scene',
                onclick: () => this.viewer.frame(),
              },
              'Frame',
            ),
          ),
          h(
            'div',
            { class: 'stage-main' },
            this.viewport,
            this.preview,
            this.emptyState,
            this.legend,
            this.pickInfo,
            this.statsPanel,
          ),
          h(
            'footer',
            { class: 'buildbar' },
            h(
              'div',
              { class: 'build-controls' },
              this.buildButton,
              this.cancelButton,
              h('label', { class: 'toggle', title: 'Build after each change' }, auto, 'Auto'),
            ),
            this.buildStatus,
            h(
              'div',
              { class: 'growth' },
              this.playButton,
              h('span', { class: 'growth-label' }, 'Age'),
              this.ageSlider,
              this.ageLabel,
            ),
          ),
          this.buildError,
        ),
      ),
      h('div', { id: 'toast', class: 'toast' }),
      (this.openDialogEl = h('dialog', { class: 'dialog', id: 'open-dialog' })),
    );

    this.viewer = new Viewer(this.viewport);
    this.viewer.onLegend = (scheme) => this.showLegend(scheme);
    this.syncColorModes();
    this.viewport.addEventListener('click', (e) => this.showPick(e));
    this.renderStats();
  }

  async start() {
    this.showTab('scene');
    try {
      [this.config] = await Promise.all([api.config().catch(() => null), this.reloadSpecies()]);
    } catch (e) {
      toast(e.message, 'error');
    }
    this.renderPanels();
    this.syncSlider();
    document.body.dataset.ready = 'true';
  }

  async reloadSpecies() {
    this.species = await api.species();
    this.details.clear();
  }

  async speciesDetail(name) {
    if (!this.details.has(name)) {
      const p = api.speciesDetail(name);
      this.details.set(name, p);
      p.catch(() => this.details.delete(name));
    }
    return this.details.get(name);
  }

  renderPanels() {
    this.scenePanel.render();
    this.environmentPanel.render();
    this.exportPanel.render();
    this.nameInput.value = this.project.name;
    if (this.tab === 'species') this.openSpeciesEditor();
  }

  showTab(id) {
    this.tab = id;
    for (const [name, el] of Object.entries(this.panels)) el.hidden = name !== id;
    for (const t of document.querySelectorAll('.tab'))
      t.classList.toggle('active', t.dataset.tab === id);
    if (id === 'species') this.openSpeciesEditor();
    if (id === 'export') this.exportPanel.render();
    if (id === 'dataset') this.datasetPanel.render();
  }

  selectedBlock() {
    return this.project.blocks[Math.max(0, this.scenePanel.selected)] ?? null;
  }

  /** Gives the selected block a species (one just saved) and shows the block. */
  useSpecies(name) {
    const block = this.selectedBlock();
    if (!block) return;
    block.species = name;
    block.parameters = {};
    this.scenePanel.render();
    this.showTab('scene');
    this.edited();
  }

  openSpeciesEditor() {
    const block = this.selectedBlock();
    const name = block?.species ?? this.species[0]?.name;
    if (name && this.speciesEditor.base !== name && !this.speciesEditor.changes.size)
      this.speciesEditor.open(name);
    else if (!this.speciesEditor.detail && name) this.speciesEditor.open(name);
  }

  showView(view) {
    for (const b of document.querySelectorAll('.seg'))
      b.classList.toggle('active', b.dataset.view === view);
    this.view = view;
    this.viewport.hidden = view !== '3d';
    this.preview.hidden = view !== 'preview';
    this.legend.hidden = view !== '3d' || !this.legend.childElementCount;
    this.statsPanel.hidden = view !== '3d';
    if (view === 'preview') this.loadPreview();
  }

  loadPreview() {
    if (!this.shownBuild) return;
    const rect = this.preview.getBoundingClientRect();
    const w = Math.max(200, Math.min(1600, Math.round(rect.width || 800)));
    const hgt = Math.max(150, Math.min(1200, Math.round((rect.height || 600) - 30)));
    const src = api.renderUrl(this.shownBuild.id, w, hgt);
    if (this.previewImg.dataset.src === src) return;
    this.previewImg.dataset.src = src;
    this.preview.dataset.state = 'loading';
    this.previewImg.onload = () => {
      this.preview.dataset.state = 'done';
    };
    this.previewImg.onerror = () => {
      this.preview.dataset.state = 'error';
    };
    this.previewImg.src = src;
  }

  // ---- building -------------------------------------------------------------

  /** Called by the panels after every change to the project. */
  edited() {
    this.checkPhysiology?.();
    this.markStale();
    if (!this.autoBuild) return;
    clearTimeout(this.buildTimer);
    this.buildTimer = setTimeout(() => this.build(), 600);
  }

  markStale() {
    const stale =
      this.shownBuild &&
      JSON.stringify(toProjectFile(this.project)) !== JSON.stringify(this.shownBuild.project);
    this.statsPanel.classList.toggle('stale', !!stale);
    this.syncSlider();
  }

  setStatus(state, text, progress) {
    this.buildStatus.dataset.state = state;
    this.progressText.textContent = text;
    if (progress !== undefined)
      this.progressBar.style.width = `${Math.round(Math.max(0, Math.min(1, progress)) * 100)}%`;
    const busy = state === 'queued' || state === 'running' || state === 'loading';
    this.cancelButton.disabled = !busy;
    this.buildStatus.classList.toggle('busy', busy);
  }

  showError(message) {
    this.buildError.hidden = !message;
    render(this.buildError, message ? [h('strong', {}, 'Build failed: '), message] : []);
  }

  /**
   * Builds the project (or grows the shown build on to later ages, `from`), then shows it.
   * Resolves to true when the scene was built and shown; a newer build supersedes it.
   */
  async build({ from } = {}) {
    clearTimeout(this.buildTimer);
    const previous = this.current;
    if (previous && (previous.state === 'queued' || previous.state === 'running')) {
      api.cancelBuild(previous.id).catch(() => {});
    }
    const project = toProjectFile(this.project);
    if (project.physiology) from = undefined; // a season is built afresh, never grown on
    const ticket = { id: null, state: 'queued' };
    this.current = ticket;
    this.showError(null);
    this.setStatus('queued', from ? 'Growing…' : 'Queued…', 0);
    let status;
    try {
      let id;
      try {
        ({ id } = await api.startBuild(project, from));
      } catch (e) {
        // The earlier build is gone (forgotten, or its plants grown on by another): build anew.
        if (!from || ![404, 409, 410].includes(e.status)) throw e;
        ({ id } = await api.startBuild(project));
      }
      if (from && this.shownBuild?.id === from) this.shownBuild.consumed = true;
      ticket.id = id;
      this.buildStatus.dataset.build = id;
      for (;;) {
        if (this.current !== ticket) return false;
        status = await api.build(id);
        if (this.current !== ticket) return false;
        ticket.state = status.state;
        if (status.state === 'done' || status.state === 'failed' || status.state === 'cancelled')
          break;
        this.setStatus(
          status.state,
          progressText(status.stage, status.progress, project),
          status.progress ?? 0,
        );
        await sleep(POLL_MS);
      }
    } catch (e) {
      if (this.current !== ticket) return false;
      this.setStatus('failed', 'Failed', 0);
      this.showError(e.message);
      return false;
    }
    if (status.state === 'cancelled') {
      this.setStatus('cancelled', 'Cancelled', 0);
      return false;
    }
    if (status.state === 'failed') {
      this.setStatus('failed', 'Failed', 0);
      this.showError(status.error ?? 'the build failed');
      return false;
    }
    this.setStatus('loading', 'Loading the scene…', 1);
    try {
      await this.viewer.load(api.sceneUrl(ticket.id, this.look), { frame: !this.shownBuild });
      this.viewport.dataset.look = lookKey(this.look);
    } catch (e) {
      if (this.current !== ticket) return false;
      this.setStatus('failed', 'Failed', 0);
      this.showError(`the scene of build ${ticket.id} does not load: ${e.message ?? e}`);
      return false;
    }
    if (this.current !== ticket) return false;
    this.syncColorModes();
    this.shownBuild = {
      id: ticket.id,
      stats: status.stats,
      age: status.ages?.[0] ?? project.blocks[0]?.age,
      project,
      key: growthKey(project),
    };
    this.emptyState.hidden = true;
    this.renderStats();
    this.markStale();
    this.setStatus('done', `Built ${ticket.id}: ${fmt(status.stats?.plants ?? 0, 0)} plants`, 1);
    if (this.view === 'preview') this.loadPreview();
    if (this.tab === 'export') this.exportPanel.render();
    return true;
  }

  async cancel() {
    const ticket = this.current;
    if (!ticket?.id) return;
    try {
      await api.cancelBuild(ticket.id);
    } catch (e) {
      toast(e.message, 'error');
    }
  }

  renderStats() {
    const s = this.shownBuild?.stats;
    const row = (label, id, value, unit, raw) =>
      h(
        'div',
        { class: 'stat' },
        h('dt', {}, label),
        h(
          'dd',
          { id, dataset: { value: raw ?? '' } },
          value,
          unit ? h('span', { class: 'unit' }, unit) : null,
        ),
      );
    render(
      this.statsPanel,
      h(
        'h3',
        {},
        'Statistics',
        h(
          'span',
          { class: 'stale-note', title: 'The project changed since this build' },
          'not built yet',
        ),
      ),
      h(
        'dl',
        {},
        row('Plants', 'stat-plants', s ? fmt(s.plants, 0) : '–', '', s?.plants),
        row('Triangles', 'stat-triangles', s ? fmt(s.triangles, 0) : '–', '', s?.triangles),
        row('Height', 'stat-height', s ? fmt(s.height, 3) : '–', 'm', s?.height),
        row('Leaf area', 'stat-leaf-area', s ? fmt(s.leaf_area, 3) : '–', 'm²', s?.leaf_area),
        row('Leaves', 'stat-leaf-count', s ? fmt(s.leaf_count, 0) : '–', '', s?.leaf_count),
        row('Objects', 'stat-objects', s ? fmt(s.objects, 0) : '–', '', s?.objects),
      ),
    );
  }

  /**
   * Changes the materials of the view and of the export (`change`: materials, textureSize) and
   * loads the shown scene again with them; #viewport's data-look says which it shows
   * ("flat", "textured:512"; "loading" meanwhile).
   */
  async setLook(change) {
    this.look = { ...this.look, ...change };
    this.lookSelect.value = this.look.materials;
    if (this.tab === 'export') this.exportPanel.render();
    const build = this.shownBuild;
    if (!build) return;
    const key = lookKey(this.look);
    this.viewport.dataset.look = 'loading';
    this.lookLoad = key;
    try {
      await this.viewer.load(api.sceneUrl(build.id, this.look));
    } catch (e) {
      if (this.lookLoad === key)
        this.showError(`the ${key} scene does not load: ${e.message ?? e}`);
      return;
    }
    if (this.lookLoad !== key || this.shownBuild !== build) return;
    this.syncColorModes();
    this.viewport.dataset.look = key;
  }

  /**
   * Enables the colour modes the shown scene has data for; a disabled one says why in its
   * tooltip. A mode that became unavailable falls back to the natural colours.
   */
  syncColorModes() {
    const table = this.viewer.model ? this.viewer.table : null;
    for (const option of this.colorSelect.options) {
      const why = this.viewer.model ? modeUnavailable(option.value, table) : null;
      option.disabled = !!why;
      option.title = why ? `Not available: ${why}` : '';
    }
    const mode = this.colorSelect.value;
    if (this.colorSelect.selectedOptions[0]?.disabled) {
      this.colorSelect.value = 'natural';
      this.viewer.setMode('natural');
    } else if (this.viewer.mode !== mode) {
      this.viewer.setMode(mode);
    }
  }

  showLegend(scheme) {
    if (!scheme) {
      render(this.legend);
      this.legend.hidden = true;
      return;
    }
    const swatch = (c) =>
      h('span', { class: 'swatch', style: { background: `rgb(${c.map(Math.round).join(',')})` } });
    const rows = (scheme.legend ?? []).map((e) =>
      h('div', { class: 'legend-row' }, swatch(e.color), e.label),
    );
    const ramp = scheme.ramp;
    if (ramp) {
      const digits = rampDigits(ramp.max - ramp.min);
      const end = (id, value) => h('span', { id, dataset: { value } }, fmt(value, digits));
      render(
        this.legend,
        h(
          'div',
          { class: 'ramp-title', id: 'legend-title' },
          ramp.label,
          h('span', { class: 'unit' }, ramp.unit),
        ),
        h('div', { class: 'ramp', style: { background: rampGradient(ramp.stops) } }),
        h('div', { class: 'ramp-labels' }, end('legend-min', ramp.min), end('legend-max', ramp.max)),
        rows,
      );
    } else {
      render(this.legend, rows);
    }
    this.legend.hidden = this.view === 'preview';
  }

  showPick(e) {
    const info = this.viewer.pick(e.clientX, e.clientY);
    if (!info) {
      this.pickInfo.hidden = true;
      return;
    }
    const parts = [info.organ.replace('_', ' ')];
    if (info.plant >= 0) parts.push(`plant ${info.plant}`);
    if (info.leaf >= 0) parts.push(`leaf ${info.leaf}`);
    if (info.rank >= 0) parts.push(`rank ${info.rank}`);
    if (info.age >= 0) parts.push(`${fmt(info.age, 1)} days old`);
    if (info.absorbed_par !== undefined)
      parts.push(`PAR ${fmt(info.absorbed_par, 1)} µmol m⁻² s⁻¹`);
    if (info.carbohydrate_concentration !== undefined)
      parts.push(`carbohydrate ${fmt(info.carbohydrate_concentration, 3)} mol C / mol C`);
    this.pickInfo.textContent = parts.join(' · ');
    this.pickInfo.hidden = false;
  }

  // ---- growth ---------------------------------------------------------------

  sceneAge() {
    return this.project.blocks[0]?.age ?? 0;
  }

  syncSlider() {
    let max = 100;
    for (const b of this.project.blocks) {
      const rec = this.species.find((s) => s.name === b.species)?.recommended_age;
      if (rec?.max) max = Math.max(max, rec.max);
      max = Math.max(max, Math.ceil(b.age));
    }
    this.ageSlider.max = String(max);
    if (!this.playing) {
      this.ageSlider.value = String(Math.round(this.sceneAge()));
      this.ageLabel.textContent = `${fmt(this.sceneAge(), 1)} d`;
    }
    this.ageSlider.disabled = !this.project.blocks.length;
  }

  /**
   * Sets the scene's age (the first block's; the others keep their difference to it) and
   * builds it: grown on from the shown build when only the ages grew, rebuilt otherwise.
   */
  setSceneAge(age) {
    const delta = age - this.sceneAge();
    for (const b of this.project.blocks) b.age = Math.max(0, b.age + delta);
    this.scenePanel.render();
    this.ageLabel.textContent = `${fmt(age, 1)} d`;
    const project = toProjectFile(this.project);
    const shown = this.shownBuild;
    const grows =
      !project.physiology &&
      shown &&
      !shown.consumed &&
      shown.key === growthKey(project) &&
      project.blocks.every((b, i) => b.age >= shown.project.blocks[i].age);
    this.markStale();
    return this.build(grows ? { from: shown.id } : {});
  }

  async togglePlay() {
    if (this.playing) {
      this.playing = false;
      return;
    }
    this.playing = true;
    render(this.playButton, icon('pause'));
    this.playButton.title = 'Pause';
    try {
      while (this.playing && this.sceneAge() < Number(this.ageSlider.max)) {
        const age = Math.floor(this.sceneAge()) + 1;
        this.ageSlider.value = String(age);
        if (!(await this.setSceneAge(age))) break;
      }
    } finally {
      this.playing = false;
      render(this.playButton, icon('play'));
      this.playButton.title = 'Grow day by day';
      this.syncSlider();
    }
  }

  // ---- project files --------------------------------------------------------

  /** The project file (JSON value) of what is being edited. */
  projectFile() {
    return toProjectFile(this.project);
  }

  loadProject(project) {
    this.project = project;
    this.scenePanel.selected = 0;
    this.renderPanels();
    this.syncSlider();
    this.markStale();
    this.shownBuild = null;
    this.build();
  }

  newProject() {
    this.loadProject(defaultProject());
  }

  async saveProject() {
    const name = this.project.name.trim();
    if (!/^[A-Za-z0-9_ -]+$/.test(name)) {
      toast(`project name '${name}': use letters, digits, spaces, _ and - only`, 'error');
      return;
    }
    try {
      const result = await api.saveProject(name, toProjectFile(this.project));
      toast(`Saved ${result.path ?? `projects/${name}.json`}`);
      document.body.dataset.saved = name;
    } catch (e) {
      toast(e.message, 'error');
    }
  }

  downloadProject() {
    const text = `${JSON.stringify(toProjectFile(this.project), null, 2)}\n`;
    download(
      new Blob([text], { type: 'application/json' }),
      `${this.project.name || 'project'}.json`,
    );
  }

  async upload() {
    const file = this.uploadInput.files[0];
    this.uploadInput.value = '';
    if (!file) return;
    try {
      const text = await file.text();
      let json;
      try {
        json = JSON.parse(text);
      } catch (e) {
        throw new Error(`not JSON: ${e.message}`);
      }
      this.loadProject(fromProjectFile(json));
      toast(`Loaded ${file.name}`);
    } catch (e) {
      toast(`${file.name}: ${e.message}`, 'error');
    }
  }

  async openDialog() {
    const dialog = this.openDialogEl;
    render(dialog, h('h2', {}, 'Open a project'), h('p', { class: 'hint' }, 'Loading…'));
    dialog.showModal();
    let names;
    try {
      names = await api.projects();
    } catch (e) {
      render(
        dialog,
        h('h2', {}, 'Open a project'),
        h('p', { class: 'error-text' }, e.message),
        h('button', { type: 'button', onclick: () => dialog.close() }, 'Close'),
      );
      return;
    }
    const open = async (name) => {
      try {
        this.loadProject(fromProjectFile(await api.project(name)));
        dialog.close();
      } catch (e) {
        toast(`${name}: ${e.message}`, 'error');
      }
    };
    render(
      dialog,
      h('h2', {}, 'Open a project'),
      names.length
        ? h(
            'ul',
            { class: 'project-list' },
            names.map((n) =>
              h(
                'li',
                {},
                h(
                  'button',
                  {
                    type: 'button',
                    class: 'link',
                    dataset: { project: n },
                    onclick: () => open(n),
                  },
                  n,
                ),
              ),
            ),
          )
        : h('p', { class: 'hint' }, 'No saved projects in the output folder yet.'),
      h(
        'div',
        { class: 'dialog-actions' },
        h('button', { type: 'button', onclick: () => dialog.close() }, 'Close'),
      ),
    );
  }
}

// The server's defaults first: the project, the colours and the formats are made from them.
const root = document.getElementById('app');
api.defaults().then(
  (served) => {
    setDefaults(served);
    const app = new App(root);
    window.plantarchBuilder = app; // for the end-to-end tests and the curious
    app.start().then(() => app.build());
  },
  (e) => {
    root.textContent = `The builder cannot start: ${e.message}`;
  },
);
