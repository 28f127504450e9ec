// The species dropdown: a button showing the chosen species (thumbnail, common and Latin
// name) that opens a searchable list of the library's species.
import { api } from './api.js';
import { h, render } from './ui.js';

function speciesLabel(s) {
  return [
    h('img', {
      class: 'thumb',
      src: api.thumbnailUrl(s.name),
      alt: '',
      loading: 'lazy',
      width: 40,
      height: 40,
    }),
    h(
      'span',
      { class: 'species-names' },
      h('span', { class: 'common' }, s.common_name || s.name),
      h('span', { class: 'latin' }, s.latin_name || s.name),
    ),
  ];
}

/**
 * A species picker for `value` (a library name or a species file); `species` is the list of
 * /api/species. Calls onChange(name).
 */
export function speciesPicker(species, value, onChange) {
  const known = species.find((s) => s.name === value);
  const current = known ?? { name: value, common_name: value, latin_name: 'species file' };
  const button = h(
    'button',
    {
      type: 'button',
      class: 'species-button',
      'aria-haspopup': 'listbox',
      dataset: { species: value },
    },
    speciesLabel(current),
    h('span', { class: 'chevron' }, '▾'),
  );
  const list = h('div', { class: 'species-list', role: 'listbox' });
  const search = h('input', {
    type: 'search',
    placeholder: 'Search species…',
    class: 'species-search',
  });
  const popup = h('div', { class: 'species-popup', hidden: true }, search, list);
  const root = h('div', { class: 'species-picker' }, button, popup);

  const fill = () => {
    const q = search.value.trim().toLowerCase();
    const shown = species.filter(
      (s) =>
        !q ||
        [s.name, s.common_name, s.latin_name, s.plant_type].some((t) =>
          (t ?? '').toLowerCase().includes(q),
        ),
    );
    render(
      list,
      shown.map((s) =>
        h(
          'button',
          {
            type: 'button',
            role: 'option',
            class: s.name === value ? 'species-option selected' : 'species-option',
            dataset: { species: s.name },
            title: s.description ?? '',
            onclick: () => {
              close();
              onChange(s.name);
            },
          },
          speciesLabel(s),
          h('span', { class: 'plant-type' }, s.plant_type ?? ''),
        ),
      ),
    );
    if (!shown.length) render(list, h('div', { class: 'empty' }, 'No species matches.'));
  };
  const outside = (e) => {
    if (!root.contains(e.target)) close();
  };
  const close = () => {
    popup.hidden = true;
    document.removeEventListener('pointerdown', outside);
  };
  button.addEventListener('click', () => {
    if (!popup.hidden) return close();
    popup.hidden = false;
    fill();
    search.focus();
    document.addEventListener('pointerdown', outside);
  });
  search.addEventListener('input', fill);
  search.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') close();
  });
  return root;
}
