// The Species tab: every parameter of a species (build parameters, phenology and each shoot
// type's table) in a form generated from the parameter table the server sends (names, units,
// valid ranges, docs as tooltips). Random fields take a constant or a uniform, normal or
// Weibull distribution. Changes are checked by the species reader on the server, whose
// one-line message is shown as it is; a valid species can be saved under a new name.
import { api } from './api.js';
import { h, render, select, toast, icon } from './ui.js';

const DISTRIBUTIONS = {
  'random number': [
    ['constant', 'constant'],
    ['uniform', 'uniform'],
    ['normal', 'normal'],
    ['weibull', 'Weibull'],
  ],
  'random whole number': [
    ['constant', 'constant'],
    ['uniform', 'uniform'],
    ['discrete', 'one of'],
  ],
};
const ARGUMENT_NAMES = {
  constant: ['value'],
  uniform: ['min', 'max'],
  normal: ['mean', 'std. dev.'],
  weibull: ['shape', 'scale'],
};

/** A random value's text split into its distribution and arguments: "uniform(1, 2)" -> {uniform, [1, 2]}. */
export function parseRandom(text) {
  const m = /^\s*(uniform|normal|weibull|discrete)\s*\((.*)\)\s*$/i.exec(text ?? '');
  if (!m) return { kind: 'constant', args: [String(text ?? '').trim()] };
  return { kind: m[1].toLowerCase(), args: m[2].split(',').map((s) => s.trim()) };
}

export function randomText(kind, args) {
  if (kind === 'constant') return args[0] ?? '';
  return `${kind}(${args.join(', ')})`;
}

// The text of one parameter's control(s), for every kind of field.
function parameterControl(p, value, onChange) {
  const kind = p.kind;
  const name = `sp-${p.key}`;
  if (kind === 'true or false') {
    const box = h('input', { type: 'checkbox', name, checked: value === 'true' });
    box.addEventListener('change', () => onChange(box.checked ? 'true' : 'false'));
    return box;
  }
  if ((kind === 'one of the values' || kind === 'choice') && p.choices?.length) {
    return select(
      p.choices.map((c) => [c.name, c.name]),
      value,
      onChange,
      { name, title: p.choices.map((c) => `${c.name}: ${c.doc}`).join('\n') },
    );
  }
  if (kind === 'number' || kind === 'whole number') {
    const input = h('input', { type: 'text', inputmode: 'decimal', name, value, class: 'num' });
    input.addEventListener('change', () => onChange(input.value.trim()));
    return input;
  }
  if (DISTRIBUTIONS[kind]) return randomControl(p, value, onChange, name);
  const input = h('input', {
    type: 'text',
    name,
    value,
    class: kind === 'three numbers' ? 'triple' : 'text',
  });
  input.addEventListener('change', () => onChange(input.value.trim()));
  return input;
}

function randomControl(p, value, onChange, name) {
  let { kind, args } = parseRandom(value);
  const inputs = h('span', { class: 'random-args' });
  const emit = () => onChange(randomText(kind, args));
  const fill = () => {
    const names = ARGUMENT_NAMES[kind] ?? null;
    if (kind === 'discrete') {
      const input = h('input', {
        type: 'text',
        name: `${name}-values`,
        value: args.join(', '),
        class: 'text',
        title: 'whole numbers, comma separated',
      });
      input.addEventListener('change', () => {
        args = input.value.split(',').map((s) => s.trim());
        emit();
      });
      render(inputs, input);
      return;
    }
    render(
      inputs,
      names.map((n, i) => {
        const input = h('input', {
          type: 'text',
          inputmode: 'decimal',
          name: `${name}-${i}`,
          value: args[i] ?? '',
          placeholder: n,
          title: n,
          class: 'num',
        });
        input.addEventListener('change', () => {
          args[i] = input.value.trim();
          emit();
        });
        return input;
      }),
    );
  };
  const kindSelect = select(
    DISTRIBUTIONS[p.kind],
    kind,
    (k) => {
      // A new distribution starts from the current value: a constant c gives uniform(c, c)...
      const first = args[0] ?? '0';
      kind = k;
      args =
        k === 'constant'
          ? [first]
          : k === 'normal'
            ? [first, '0']
            : k === 'weibull'
              ? ['1', first]
              : [first, args[1] ?? first];
      fill();
      emit();
    },
    { name: `${name}-kind`, class: 'dist' },
  );
  fill();
  return h('span', { class: 'random' }, kindSelect, inputs);
}

function groupTitle(prefix) {
  if (!prefix) return 'Shoot';
  const last = prefix.split('.').pop();
  return last.charAt(0).toUpperCase() + last.slice(1).replaceAll('_', ' ');
}

export class SpeciesEditor {
  constructor(app, container) {
    this.app = app;
    this.container = container;
    this.base = null;
    this.detail = null;
    this.changes = new Map(); // key ("shoot_types.LABEL.PATH", ...) -> value text
    this.rows = [];
    this.checkTimer = null;
    this.checkSerial = 0;
  }

  async open(name) {
    this.base = name;
    this.changes.clear();
    render(this.container, h('p', { class: 'hint' }, `Loading ${name}…`));
    try {
      this.detail = await this.app.speciesDetail(name);
    } catch (e) {
      render(this.container, h('p', { class: 'error-text' }, e.message));
      return;
    }
    this.render();
  }

  // The parameters of the species, as sections of groups: [{title, prefix, params}].
  sections() {
    const d = this.detail;
    const out = [];
    const withKey = (list, prefix) =>
      (list ?? []).map((p) => ({ ...p, key: `${prefix}.${p.path ?? p.name}` }));
    if (d.build_parameters?.length) {
      out.push({
        title: 'Build parameters',
        groups: [{ title: '', params: withKey(d.build_parameters, 'build_parameters') }],
      });
    }
    if (d.phenology?.length)
      out.push({
        title: 'Phenology',
        groups: [{ title: '', params: withKey(d.phenology, 'phenology') }],
      });
    for (const [label, list] of Object.entries(d.shoot_types ?? {})) {
      const groups = new Map();
      for (const p of withKey(list, `shoot_types.${label}`)) {
        const prefix = (p.path ?? '').split('.').slice(0, -1).join('.');
        if (!groups.has(prefix)) groups.set(prefix, { title: groupTitle(prefix), params: [] });
        groups.get(prefix).params.push(p);
      }
      out.push({ title: `Shoot type: ${label}`, groups: [...groups.values()] });
    }
    return out;
  }

  render() {
    const d = this.detail;
    this.rows = [];
    const filter = h('input', {
      type: 'search',
      placeholder: 'Filter parameters…',
      name: 'species-filter',
    });
    const onlyChanged = h('input', { type: 'checkbox', name: 'only-changed' });
    const applyFilter = () => {
      const q = filter.value.trim().toLowerCase();
      for (const row of this.rows) {
        const match =
          (!q || row.dataset.search.includes(q)) &&
          (!onlyChanged.checked || this.changes.has(row.dataset.key));
        row.hidden = !match;
      }
      for (const group of this.container.querySelectorAll('details.param-group')) {
        group.hidden = ![...group.querySelectorAll('.param-row')].some((r) => !r.hidden);
        if (q || onlyChanged.checked) group.open = !group.hidden;
      }
      for (const section of this.container.querySelectorAll('.param-section')) {
        section.hidden = ![...section.querySelectorAll('.param-row')].some((r) => !r.hidden);
      }
    };
    filter.addEventListener('input', applyFilter);
    onlyChanged.addEventListener('change', applyFilter);

    const speciesSelect = select(
      this.app.species.map((s) => [s.name, `${s.common_name || s.name} (${s.name})`]),
      this.base,
      (name) => this.open(name),
      { name: 'species-base' },
    );
    this.status = h(
      'div',
      { id: 'species-status', class: 'species-status', dataset: { state: 'unchanged' } },
      'No changes.',
    );
    this.nameInput = h('input', {
      type: 'text',
      name: 'species-name',
      value: `my_${this.base}`,
      pattern: '[A-Za-z0-9_\\-]+',
    });
    const saveButton = h(
      'button',
      { type: 'button', class: 'primary', id: 'species-save', onclick: () => this.save() },
      'Save as new species',
    );

    const sections = this.sections().map((section, si) =>
      h(
        'section',
        { class: 'param-section' },
        h('h3', {}, section.title),
        section.groups.map((g, gi) => {
          const rows = g.params.map((p) => this.row(p));
          if (!g.title) return h('div', { class: 'param-rows' }, rows);
          return h(
            'details',
            { class: 'param-group', open: si === 0 && gi === 0 },
            h('summary', {}, g.title, h('span', { class: 'count' }, String(rows.length))),
            rows,
          );
        }),
      ),
    );
    render(
      this.container,
      h(
        'div',
        { class: 'species-head' },
        h(
          'label',
          { class: 'field wide' },
          h('span', { class: 'field-label' }, 'Species to edit'),
          speciesSelect,
        ),
        h(
          'p',
          { class: 'hint', title: d.description ?? '' },
          h('em', {}, d.latin_name ?? ''),
          d.description ? ` — ${d.description}` : '',
        ),
        h(
          'div',
          { class: 'filter-row' },
          filter,
          h('label', { class: 'toggle' }, onlyChanged, 'changed only'),
        ),
      ),
      h('div', { class: 'param-list' }, sections),
      h(
        'div',
        { class: 'species-foot' },
        this.status,
        h(
          'div',
          { class: 'save-row' },
          h(
            'label',
            { class: 'field' },
            h('span', { class: 'field-label' }, 'New species name'),
            this.nameInput,
          ),
          saveButton,
        ),
      ),
    );
  }

  row(p) {
    const original = p.value ?? '';
    const current = this.changes.get(p.key) ?? original;
    const range = p.range; // the server's wording (plantarch's rangeText)
    const tip = [
      p.doc,
      p.kind ? `kind: ${p.kind}` : '',
      range ? `valid: ${range}` : '',
      p.unit ? `unit: ${p.unit}` : '',
      `species value: ${original === '' ? '(none)' : original}`,
    ]
      .filter(Boolean)
      .join('\n');
    const row = h('div', {
      class: 'param-row',
      dataset: { key: p.key, search: `${p.path ?? p.name} ${p.doc ?? ''}`.toLowerCase() },
    });
    const reset = h(
      'button',
      {
        type: 'button',
        class: 'icon reset',
        title: `Back to ${original}`,
        hidden: !this.changes.has(p.key),
      },
      icon('reset'),
    );
    const onChange = (text) => {
      if (text === original) this.changes.delete(p.key);
      else this.changes.set(p.key, text);
      row.classList.toggle('changed', this.changes.has(p.key));
      reset.hidden = !this.changes.has(p.key);
      this.scheduleCheck();
    };
    const control = h('span', { class: 'param-control' }, parameterControl(p, current, onChange));
    reset.addEventListener('click', () => {
      onChange(original);
      render(control, parameterControl(p, original, onChange));
    });
    row.append(
      h(
        'span',
        { class: 'param-name', title: tip },
        p.name.replaceAll('_', ' '),
        p.unit ? h('span', { class: 'unit' }, p.unit) : null,
      ),
      control,
      reset,
    );
    if (this.changes.has(p.key)) row.classList.add('changed');
    this.rows.push(row);
    return row;
  }

  body() {
    return {
      base: this.base,
      name: this.nameInput?.value.trim() || `my_${this.base}`,
      changes: Object.fromEntries(this.changes),
    };
  }

  setStatus(state, text) {
    this.status.dataset.state = state;
    this.status.textContent = text;
    for (const row of this.rows) row.classList.remove('invalid');
    if (state === 'invalid') {
      // The field the message names, when it names one of the changed fields.
      const keys = [...this.changes.keys()].filter((k) => text.includes(k.split('.').slice(-1)[0]));
      for (const row of this.rows) if (keys.includes(row.dataset.key)) row.classList.add('invalid');
    }
  }

  scheduleCheck() {
    clearTimeout(this.checkTimer);
    if (!this.changes.size) {
      this.setStatus('unchanged', 'No changes.');
      return;
    }
    this.setStatus('checking', 'Checking…');
    this.checkTimer = setTimeout(() => this.check(), 300);
  }

  async check() {
    const serial = ++this.checkSerial;
    try {
      await api.checkSpecies(this.body());
      if (serial === this.checkSerial)
        this.setStatus(
          'valid',
          `✓ ${this.changes.size} change${this.changes.size === 1 ? '' : 's'}, valid`,
        );
      return true;
    } catch (e) {
      if (serial === this.checkSerial) this.setStatus('invalid', e.message);
      return false;
    }
  }

  async save() {
    const body = this.body();
    if (!/^[A-Za-z0-9_-]+$/.test(body.name)) {
      this.setStatus('invalid', `species name '${body.name}': use letters, digits, _ and - only`);
      return;
    }
    try {
      const result = await api.saveSpecies(body);
      const name = result.name ?? body.name;
      await this.app.reloadSpecies();
      this.setStatus('saved', `Saved ${result.path}. `);
      const block = this.app.selectedBlock();
      if (block) {
        this.status.append(
          h(
            'button',
            {
              type: 'button',
              class: 'link',
              id: 'species-use',
              onclick: () => this.app.useSpecies(name),
            },
            `Use ${name} in block ${block.name}`,
          ),
        );
      }
      toast(`Saved species ${name} (${result.path})`);
    } catch (e) {
      this.setStatus('invalid', e.message);
    }
  }
}
