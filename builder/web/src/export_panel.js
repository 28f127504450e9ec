// The Export tab: the shown build written as OBJ, PLY, glTF/GLB, USD or plant XML, the whole
// scene or one file per plant, downloaded (a zip for many files) or written into a folder
// under the builder's output folder.
import { api } from './api.js';
import { defaults } from './defaults.js';
import { h, render, field, select, checkbox, toast } from './ui.js';

/** The export formats as [format, label] options, from the server's table. */
export function formatOptions() {
  return defaults().export_formats.map((f) => [f.format, `${f.description} (.${f.format})`]);
}

export class ExportPanel {
  constructor(app, container) {
    this.app = app;
    this.container = container;
    this.format = 'glb';
    this.perPlant = false;
    this.folder = 'exports';
    this.name = 'scene';
  }

  render() {
    const folder = h('input', {
      type: 'text',
      name: 'export-folder',
      value: this.folder,
      placeholder: 'exports',
    });
    folder.addEventListener('input', () => {
      this.folder = folder.value;
    });
    const name = h('input', { type: 'text', name: 'export-name', value: this.name });
    name.addEventListener('input', () => {
      this.name = name.value;
    });
    this.result ??= h('div', { id: 'export-result', class: 'export-result' });
    const build = this.app.shownBuild;
    render(
      this.container,
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Export'),
        build
          ? h(
              'p',
              { class: 'hint' },
              `The scene shown: build ${build.id}, ${build.stats?.plants ?? 0} plants at ${build.age ?? '–'} days.`,
            )
          : h('p', { class: 'hint' }, 'Build the scene first.'),
        field(
          'Format',
          select(
            formatOptions(),
            this.format,
            (v) => {
              this.format = v;
            },
            { name: 'export-format' },
          ),
          { wide: true },
        ),
        h(
          'label',
          { class: 'toggle' },
          checkbox(
            this.perPlant,
            (v) => {
              this.perPlant = v;
            },
            { name: 'per-plant' },
          ),
          'One file per plant',
        ),
      ),
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Download'),
        h('p', { class: 'hint' }, 'Many files come as one zip.'),
        h(
          'button',
          {
            type: 'button',
            id: 'export-download',
            disabled: !build,
            onclick: () => this.download(),
          },
          'Download',
        ),
      ),
      h(
        'section',
        { class: 'group' },
        h('h2', {}, 'Into the output folder'),
        this.app.config?.output
          ? h('p', { class: 'hint' }, 'Output folder: ', h('code', {}, this.app.config.output))
          : null,
        h(
          'div',
          { class: 'grid2' },
          field('Folder', folder, {
            title: `a folder under the output folder${this.app.config?.output ? ` (${this.app.config.output})` : ''}`,
          }),
          field('File name', name, {
            title: 'without extension; one file per plant adds the plant number',
          }),
        ),
        h(
          'button',
          {
            type: 'button',
            class: 'primary',
            id: 'export-write',
            disabled: !build,
            onclick: () => this.write(),
          },
          'Write files',
        ),
        this.result,
      ),
    );
  }

  download() {
    const build = this.app.shownBuild;
    if (!build) return;
    const a = h('a', {
      href: api.downloadUrl({
        build: build.id,
        format: this.format,
        per_plant: this.perPlant,
        name: this.name.trim(),
      }),
      download: '',
    });
    document.body.append(a);
    a.click();
    a.remove();
  }

  async write() {
    const build = this.app.shownBuild;
    if (!build) return;
    this.result.dataset.state = 'writing';
    render(this.result, h('p', { class: 'hint' }, 'Writing…'));
    try {
      const { files } = await api.exportFiles({
        build: build.id,
        format: this.format,
        per_plant: this.perPlant,
        folder: this.folder.trim(),
        name: this.name.trim() || 'scene',
      });
      this.result.dataset.state = 'done';
      render(
        this.result,
        h('p', {}, `Wrote ${files.length} file${files.length === 1 ? '' : 's'}:`),
        h(
          'ul',
          { class: 'file-list' },
          files.map((f) => h('li', {}, h('code', {}, f))),
        ),
      );
      toast(`Wrote ${files.length} file${files.length === 1 ? '' : 's'} under the output folder`);
    } catch (e) {
      this.result.dataset.state = 'error';
      render(this.result, h('p', { class: 'error-text' }, e.message));
    }
  }
}
