// The Export tab: the shown build written as OBJ, PLY, glTF/GLB, USD or plant XML, the whole
// scene or one file per plant, with its variant (materials, nodes, levels of detail, meshopt
// compression, skin: the command line's options, builder/API.md), downloaded (a zip for many
// files) or written into a folder under the builder's output folder. The materials chosen here
// are the view's too (app.look).
import { api } from './api.js';
import { defaults } from './defaults.js';
import { h, render, field, select, checkbox, toast, download } from './ui.js';

export const TEXTURE_SIZES = [64, 128, 256, 512, 1024, 2048, 4096];
const NODE_LEVELS = [
  ['kind', 'A mesh per organ kind (default)'],
  ['plant', 'A mesh per plant'],
  ['organ', 'A node per organ (pick one leaf or fruit)'],
];
const INSTANCING = [
  ['shared', 'Organs of one shape share a mesh (default)'],
  ['gpu', 'GPU instances (EXT_mesh_gpu_instancing; not Blender 3.4)'],
  ['none', 'A mesh per organ'],
];
const LEVELS = [
  ['', 'None'],
  ['reduced', 'Reduced (a quarter of the triangles)'],
  ['reduced,cards', 'Reduced, then cards'],
  ['cards', 'Cards'],
];

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
    this.nodes = 'kind';
    this.instancing = 'shared';
    this.lod = '';
    this.meshopt = false;
    this.skin = false;
    this.atlas = true;
  }

  /** The export's variant as the API's fields, those that differ from the defaults. */
  variant() {
    const v = {};
    const look = this.app.look;
    if (look.materials === 'textured') {
      v.materials = 'textured';
      v.texture_size = look.textureSize;
      if (!this.atlas) v.atlas = false;
    }
    if (this.nodes !== 'kind') v.nodes = this.nodes;
    if (this.nodes === 'organ' && this.instancing !== 'shared') v.instancing = this.instancing;
    if (this.lod) v.lod = this.lod;
    if (this.meshopt) v.meshopt = true;
    if (this.skin) v.skin = true;
    return v;
  }

  /** The variant's controls (those that apply to the chosen settings shown). */
  variantControls() {
    const look = this.app.look;
    const set = (key) => (v) => {
      this[key] = v;
      this.render();
    };
    return h(
      'section',
      { class: 'group', id: 'export-variant' },
      h('h2', {}, 'Variant'),
      h(
        'p',
        { class: 'hint' },
        'Materials: OBJ, glTF and USD; nodes and skin: glTF and USD; levels of detail and ' +
          'meshopt: glTF. The view shows the materials chosen.',
      ),
      h(
        'div',
        { class: 'grid2' },
        field(
          'Materials',
          select(
            [
              ['flat', 'Flat colours'],
              ['textured', 'Procedural textures'],
            ],
            look.materials,
            (v) => this.app.setLook({ materials: v }),
            { name: 'export-materials' },
          ),
        ),
        look.materials === 'textured'
          ? field(
              'Texture size',
              select(
                TEXTURE_SIZES.map((n) => [String(n), `${n} × ${n}`]),
                String(look.textureSize),
                (v) => this.app.setLook({ textureSize: Number(v) }),
                { name: 'export-texture-size' },
              ),
              { title: 'texels a side of each texture' },
            )
          : null,
      ),
      look.materials === 'textured'
        ? h(
            'label',
            { class: 'toggle', title: 'off: --no-texture-atlas' },
            checkbox(this.atlas, set('atlas'), { name: 'export-atlas' }),
            "Texture atlas: the leaves' maps in one image, read through texture transforms",
          )
        : null,
      field('Nodes', select(NODE_LEVELS, this.nodes, set('nodes'), { name: 'export-nodes' }), {
        wide: true,
      }),
      this.nodes === 'organ'
        ? field(
            'Instancing',
            select(INSTANCING, this.instancing, set('instancing'), { name: 'export-instancing' }),
            { wide: true, title: '--instancing' },
          )
        : null,
      field('Levels of detail', select(LEVELS, this.lod, set('lod'), { name: 'export-lod' }), {
        wide: true,
      }),
      h(
        'label',
        { class: 'toggle' },
        checkbox(this.meshopt, set('meshopt'), { name: 'export-meshopt' }),
        'Meshopt compression (not read by Blender 3.4)',
      ),
      h(
        'label',
        { class: 'toggle' },
        checkbox(this.skin, set('skin'), { name: 'export-skin' }),
        'Skin: a wind-ready skeleton',
      ),
    );
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
      this.variantControls(),
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

  /** Fetches the download (so that a refusal shows its line here) and saves it. */
  async download() {
    const build = this.app.shownBuild;
    if (!build) return;
    const url = api.downloadUrl(
      { build: build.id, format: this.format, per_plant: this.perPlant, name: this.name.trim() },
      this.variant(),
    );
    this.result.dataset.state = 'downloading';
    render(this.result, h('p', { class: 'hint' }, 'Preparing the download…'));
    try {
      const response = await fetch(url);
      if (!response.ok) {
        const data = await response.json().catch(() => ({}));
        throw new Error(data.error ?? `HTTP ${response.status}`);
      }
      const disposition = response.headers.get('Content-Disposition') ?? '';
      const name = /filename="([^"]+)"/.exec(disposition)?.[1] ?? 'scene';
      download(await response.blob(), name);
      this.result.dataset.state = 'downloaded';
      render(this.result, h('p', {}, 'Downloaded ', h('code', {}, name), '.'));
    } catch (e) {
      this.result.dataset.state = 'error';
      render(this.result, h('p', { class: 'error-text' }, e.message));
    }
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
        ...this.variant(),
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
