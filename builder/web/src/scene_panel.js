// The Scene tab: the blocks of plants (add, edit, duplicate, delete) and, per block, its
// species, layout, counts, age, seed, build parameters and trellis.
import { defaultBlock, duplicateBlock, blockName, positions } from './project.js';
import { speciesPicker } from './species_picker.js';
import { h, render, field, numberInput, vectorInput, select, checkbox, fmt, icon } from './ui.js';

export class ScenePanel {
  /** `app` gives project, species, speciesDetail(name) and edited(). */
  constructor(app, container) {
    this.app = app;
    this.container = container;
    this.selected = 0;
  }

  get blocks() {
    return this.app.project.blocks;
  }

  render() {
    this.selected = Math.min(this.selected, this.blocks.length - 1);
    render(
      this.container,
      h(
        'div',
        { class: 'panel-head' },
        h('h2', {}, 'Blocks'),
        h(
          'button',
          { type: 'button', class: 'small', id: 'add-block', onclick: () => this.add() },
          '+ Add block',
        ),
      ),
      h(
        'div',
        { class: 'block-list' },
        this.blocks.map((b, i) => this.card(b, i)),
      ),
      this.blocks.length ? null : h('p', { class: 'hint' }, 'No blocks: add one to place plants.'),
    );
  }

  card(b, i) {
    const open = i === this.selected;
    const summary = h('span', { class: 'block-summary' }, this.summary(b));
    const head = h(
      'div',
      {
        class: 'block-head',
        onclick: () => {
          this.selected = open ? -1 : i;
          this.render();
        },
      },
      h('span', { class: 'block-name' }, b.name),
      h('span', { class: 'block-species' }, this.speciesName(b.species)),
      summary,
      h(
        'span',
        { class: 'block-actions' },
        h(
          'button',
          {
            type: 'button',
            class: 'icon',
            title: 'Duplicate block',
            dataset: { action: 'duplicate' },
            onclick: (e) => {
              e.stopPropagation();
              this.duplicate(i);
            },
          },
          icon('copy'),
        ),
        h(
          'button',
          {
            type: 'button',
            class: 'icon danger',
            title: 'Delete block',
            dataset: { action: 'delete' },
            onclick: (e) => {
              e.stopPropagation();
              this.remove(i);
            },
          },
          icon('trash'),
        ),
      ),
    );
    const card = h(
      'div',
      { class: open ? 'block-card open' : 'block-card', dataset: { block: b.name } },
      head,
    );
    if (open)
      card.append(
        this.editor(b, () => {
          summary.textContent = this.summary(b);
        }),
      );
    return card;
  }

  speciesName(name) {
    const s = this.app.species.find((x) => x.name === name);
    return s?.common_name || name;
  }

  summary(b) {
    const layout =
      b.layout === 'grid'
        ? `${b.count[0]}×${b.count[1]} grid`
        : b.layout === 'scatter'
          ? `${b.plants} scattered`
          : b.layout === 'skeleton'
            ? `skeleton ${b.skeleton.file || '(no file)'}`
            : 'single plant';
    return `${layout} · ${fmt(b.age, 1)} d`;
  }

  editor(b, refresh) {
    const edited = (rerender = false) => {
      refresh();
      if (rerender) this.render();
      this.app.edited();
    };
    const set = (key, rerender) => (v) => {
      b[key] = v;
      edited(rerender);
    };
    const layoutFields = h('div', { class: 'grid2' });
    const fillLayout = () => {
      if (b.layout === 'grid') {
        render(
          layoutFields,
          field(
            'Plants x, y',
            vectorInput(b.count, set('count'), { min: 1, integer: true, name: 'count' }),
            { wide: true },
          ),
          field(
            'Spacing x, y',
            vectorInput(b.spacing, set('spacing'), { min: 0.001, step: 0.05, name: 'spacing' }),
            { unit: 'm', wide: true },
          ),
        );
      } else if (b.layout === 'scatter') {
        render(
          layoutFields,
          field(
            'Plants',
            numberInput(b.plants, set('plants'), { min: 1, integer: true, name: 'plants' }),
          ),
          field(
            'Area x, y',
            vectorInput(b.area, set('area'), { min: 0, step: 0.1, name: 'area' }),
            { unit: 'm', wide: true },
          ),
        );
      } else if (b.layout === 'skeleton') {
        render(layoutFields, ...this.skeletonFields(b, edited));
      } else {
        render(layoutFields);
      }
      // Build parameters, germination and trellis do not apply to a measured skeleton.
      for (const el of [params, trellis, buildHeading])
        if (el) el.hidden = b.layout === 'skeleton';
      germination.hidden = b.layout !== 'grid' && b.layout !== 'scatter';
    };
    const speciesInfo = this.app.species.find((s) => s.name === b.species);
    const recommended = speciesInfo?.recommended_age;
    const params = h(
      'div',
      { class: 'build-params' },
      h('p', { class: 'hint' }, 'Loading build parameters…'),
    );
    this.fillParameters(b, params, edited);
    const germination = field(
      'Germination',
      numberInput(b.germination, set('germination'), {
        min: 0,
        max: 1,
        step: 0.05,
        name: 'germination',
      }),
      { title: 'probability that a position gets a plant, 0 to 1' },
    );
    // Only a species that declares a trellis has one to draw.
    const trellis = speciesInfo?.trellis
      ? field('Trellis', checkbox(b.trellis, set('trellis'), { name: 'trellis' }), {
          title: "the species' trellis posts and wires",
        })
      : null;
    const buildHeading = h('h3', {}, 'Build parameters');
    fillLayout();
    return h(
      'div',
      { class: 'block-editor' },
      h(
        'div',
        { class: 'grid2' },
        field('Name', this.nameInput(b, refresh)),
        field(
          'Layout',
          select(
            [
              ['grid', 'Grid'],
              ['scatter', 'Scatter'],
              ['single', 'Single plant'],
              ['skeleton', 'Measured skeleton'],
            ],
            b.layout,
            (v) => {
              b.layout = v;
              fillLayout();
              edited();
            },
            { name: 'layout' },
          ),
        ),
      ),
      field(
        'Species',
        speciesPicker(this.app.species, b.species, (name) => {
          b.species = name;
          b.parameters = {};
          const rec = this.app.species.find((s) => s.name === name)?.recommended_age;
          if (rec?.default !== undefined) b.age = rec.default;
          edited(true);
        }),
        { wide: true },
      ),
      field('Origin x, y, z', vectorInput(b.origin, set('origin'), { step: 0.1, name: 'origin' }), {
        unit: 'm',
        wide: true,
      }),
      layoutFields,
      h(
        'div',
        { class: 'grid2' },
        field('Age', numberInput(b.age, set('age'), { min: 0, step: 1, name: 'age' }), {
          unit: 'days',
          title: recommended
            ? `recommended: ${recommended.min} to ${recommended.max} days`
            : undefined,
        }),
        germination,
        field('Seed', this.seedInput(b, edited), {
          title: "the block's random seed; empty: the project's",
        }),
        trellis,
      ),
      h('h3', {}, 'Bending'),
      h(
        'div',
        { class: 'grid2' },
        field('Bend under load', checkbox(!!b.bend, set('bend'), { name: 'bend' }), {
          title:
            "the shoots bend under their own weight, leaves and fruit (the species' mechanics; " +
            'docs/measured-plants.md)',
        }),
        field('Elastic modulus', this.modulusInput(b, edited), {
          unit: 'Pa',
          title:
            "Young's modulus of the stems, 1e5 to 1e12 (green wood 1e9 to 1e10, herbaceous " +
            "1e8 to 1e9); empty: the species'",
        }),
      ),
      buildHeading,
      params,
    );
  }

  // A skeleton block's file (relative to OUTPUT/projects/, as obstacle files are), its unit
  // and the spacing its axes are resampled to.
  skeletonFields(b, edited) {
    const file = h('input', {
      type: 'text',
      name: 'skeleton-file',
      value: b.skeleton.file,
      placeholder: '../skeletons/plant.csv',
      spellcheck: false,
    });
    file.addEventListener('change', () => {
      b.skeleton.file = file.value.trim();
      edited();
    });
    const units = [
      ['1', 'm'],
      ['0.01', 'cm'],
      ['0.001', 'mm'],
    ];
    const unit = String(b.skeleton.unit);
    if (!units.some(([v]) => v === unit)) units.push([unit, `${unit} m`]);
    return [
      field('Skeleton file', file, {
        wide: true,
        title:
          'a measured skeleton: a node table (.csv), .json or .mtg file, relative to ' +
          "OUTPUT/projects/ (the output folder's files only)",
      }),
      field(
        'Units',
        select(
          units,
          unit,
          (v) => {
            b.skeleton.unit = parseFloat(v);
            edited();
          },
          { name: 'skeleton-unit' },
        ),
        { title: "the skeleton's coordinates and radii" },
      ),
      field(
        'Resample',
        numberInput(b.skeleton.spacing, (v) => ((b.skeleton.spacing = v), edited()), {
          min: 0,
          max: 10,
          step: 0.01,
          name: 'skeleton-spacing',
        }),
        { unit: 'm', title: 'internodes of about this length (0: every point is a node)' },
      ),
    ];
  }

  modulusInput(b, edited) {
    const input = h('input', {
      type: 'number',
      min: 1e5,
      max: 1e12,
      step: 'any',
      value: b.elastic_modulus ?? '',
      placeholder: "species'",
      name: 'elastic-modulus',
    });
    input.addEventListener('change', () => {
      const v = parseFloat(input.value);
      b.elastic_modulus = Number.isFinite(v) ? v : null;
      edited();
    });
    return input;
  }

  nameInput(b, refresh) {
    const input = h('input', { type: 'text', value: b.name, name: 'name' });
    input.addEventListener('change', () => {
      const name = input.value.trim();
      if (!name || this.blocks.some((x) => x !== b && x.name === name)) {
        input.value = b.name;
        return;
      }
      b.name = name;
      refresh();
      this.render();
      this.app.edited();
    });
    return input;
  }

  seedInput(b, edited) {
    const input = h('input', {
      type: 'number',
      min: 0,
      step: 1,
      value: b.seed ?? '',
      placeholder: `project's (${this.app.project.seed})`,
      name: 'seed',
    });
    input.addEventListener('change', () => {
      const v = parseInt(input.value, 10);
      b.seed = Number.isFinite(v) ? v : null;
      edited();
    });
    return input;
  }

  async fillParameters(b, container, edited) {
    let detail;
    try {
      detail = await this.app.speciesDetail(b.species);
    } catch (e) {
      render(container, h('p', { class: 'error-text' }, e.message));
      return;
    }
    const list = detail.build_parameters ?? [];
    if (!list.length) {
      render(container, h('p', { class: 'hint' }, 'This species has no build parameters.'));
      return;
    }
    render(
      container,
      h(
        'div',
        { class: 'grid2' },
        list.map((p) => {
          const input = h('input', {
            type: 'number',
            step: 'any',
            min: p.min,
            max: p.max,
            name: `param-${p.name}`,
            value: b.parameters[p.name] ?? '',
            placeholder: String(p.value),
          });
          input.addEventListener('change', () => {
            const v = parseFloat(input.value);
            if (Number.isFinite(v)) b.parameters[p.name] = v;
            else delete b.parameters[p.name];
            edited();
          });
          const title = `${p.doc ?? ''}${p.doc ? '\n' : ''}valid: ${p.range ?? `${p.min} to ${p.max}`}; default ${p.value}`;
          return field(p.name.replaceAll('_', ' '), input, { unit: p.unit, title });
        }),
      ),
    );
  }

  add() {
    const last = this.blocks[this.blocks.length - 1];
    const b = defaultBlock(this.blocks.length, last?.species ?? 'bean');
    b.name = this.freeName();
    if (last) b.origin = [last.origin[0] + this.extent(last) + 0.5, last.origin[1], last.origin[2]];
    this.blocks.push(b);
    this.selected = this.blocks.length - 1;
    this.render();
    this.app.edited();
  }

  duplicate(i) {
    const copy = duplicateBlock(this.blocks[i], 0);
    copy.name = this.freeName();
    copy.origin = [
      copy.origin[0],
      copy.origin[1] + this.extent(this.blocks[i], 1) + 0.5,
      copy.origin[2],
    ];
    this.blocks.splice(i + 1, 0, copy);
    this.selected = i + 1;
    this.render();
    this.app.edited();
  }

  remove(i) {
    this.blocks.splice(i, 1);
    this.selected = Math.min(this.selected, this.blocks.length - 1);
    this.render();
    this.app.edited();
  }

  freeName() {
    for (let i = 0; ; i++) {
      const name = blockName(i);
      if (!this.blocks.some((b) => b.name === name)) return name;
    }
  }

  /** A block's size along x (axis 0) or y (1), m. */
  extent(b, axis = 0) {
    if (b.layout === 'grid') return (b.count[axis] - 1) * b.spacing[axis];
    if (b.layout === 'scatter') return b.area[axis];
    return 0;
  }

  /** Plant positions over every block (before germination), for the status line. */
  positions() {
    return this.blocks.reduce((n, b) => n + positions(b), 0);
  }
}
