// Small DOM helpers: element construction, labelled form rows, a toast for messages.

/** Creates an element: h('button', {class: 'primary', onclick}, 'Build'). */
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs ?? {})) {
    if (value === undefined || value === null || value === false) continue;
    if (key.startsWith('on') && typeof value === 'function')
      el.addEventListener(key.slice(2), value);
    else if (key === 'class') el.className = value;
    else if (key === 'dataset') Object.assign(el.dataset, value);
    else if (key === 'style' && typeof value === 'object') Object.assign(el.style, value);
    else if (key in el && typeof value !== 'string') el[key] = value;
    else el.setAttribute(key, value === true ? '' : String(value));
  }
  append(el, children);
  return el;
}

function append(el, children) {
  for (const child of children.flat(Infinity)) {
    if (child === undefined || child === null || child === false) continue;
    el.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
}

/** Replaces the children of `el`. */
export function render(el, ...children) {
  el.replaceChildren();
  append(el, children);
  return el;
}

/** A form row: a label (with a tooltip) above or beside its control. */
export function field(label, control, { title, unit, wide } = {}) {
  return h(
    'label',
    { class: wide ? 'field wide' : 'field', title },
    h('span', { class: 'field-label' }, label, unit ? h('span', { class: 'unit' }, unit) : null),
    control,
  );
}

/** A number input bound to a getter and a setter; `step` and bounds as in HTML. */
export function numberInput(value, onChange, { min, max, step = 'any', name, integer } = {}) {
  const input = h('input', {
    type: 'number',
    value: String(value ?? ''),
    min,
    max,
    step: integer ? 1 : step,
    name,
  });
  input.addEventListener('change', () => {
    const v = integer ? parseInt(input.value, 10) : parseFloat(input.value);
    if (Number.isFinite(v)) onChange(v);
  });
  return input;
}

/** Two or three number inputs side by side (x, y[, z]). */
export function vectorInput(values, onChange, options = {}) {
  const current = [...values];
  return h(
    'div',
    { class: 'vector' },
    current.map((v, i) =>
      numberInput(
        v,
        (x) => {
          current[i] = x;
          onChange([...current]);
        },
        { ...options, name: options.name ? `${options.name}-${'xyz'[i]}` : undefined },
      ),
    ),
  );
}

export function select(options, value, onChange, attrs = {}) {
  const el = h(
    'select',
    attrs,
    options.map(([v, text]) => h('option', { value: v, selected: v === value }, text)),
  );
  el.addEventListener('change', () => onChange(el.value));
  return el;
}

export function checkbox(checked, onChange, attrs = {}) {
  const el = h('input', { type: 'checkbox', checked, ...attrs });
  el.addEventListener('change', () => onChange(el.checked));
  return el;
}

let toastTimer = null;
/** Shows a short message at the bottom of the window; errors stay until dismissed. */
export function toast(message, kind = 'info') {
  const el = document.getElementById('toast');
  if (!el) return;
  clearTimeout(toastTimer);
  render(
    el,
    h('span', {}, message),
    h(
      'button',
      { class: 'icon', title: 'Dismiss', onclick: () => el.classList.remove('shown') },
      icon('close'),
    ),
  );
  el.className = `toast shown ${kind}`;
  if (kind !== 'error') toastTimer = setTimeout(() => el.classList.remove('shown'), 4000);
}

/** Formats a number with at most `digits` decimals and thousands separators ('–' for none). */
export function fmt(x, digits = 3) {
  if (x === undefined || x === null || !Number.isFinite(x)) return '–';
  return Number(x.toFixed(digits)).toLocaleString('en-US');
}

/** Saves `blob` as a download named `name`. */
export function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = h('a', { href: url, download: name });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

const ICONS = {
  copy: 'M8 8h11v11H8zM5 16V5h11',
  trash: 'M5 7h14M10 7V4h4v3M7 7l1 13h8l1-13',
  play: 'M8 5l11 7-11 7z',
  pause: 'M8 5v14M16 5v14',
  reset: 'M4 12a8 8 0 1 0 3-6.2M4 4v4h4',
  close: 'M6 6l12 12M18 6L6 18',
};
/** A small stroked SVG icon (no icon font: the page loads nothing from elsewhere). */
export function icon(name) {
  const ns = 'http://www.w3.org/2000/svg';
  const svg = document.createElementNS(ns, 'svg');
  svg.setAttribute('viewBox', '0 0 24 24');
  svg.setAttribute('class', `svg-icon icon-${name}`);
  svg.setAttribute('aria-hidden', 'true');
  const path = document.createElementNS(ns, 'path');
  path.setAttribute('d', ICONS[name]);
  svg.append(path);
  return svg;
}
