// The Environment tab's physiology section: a season of the carbohydrate budget and/or the
// nitrogen model over the last days of the plants' growth (the project file's `physiology`,
// builder/API.md), its light traced through the scene each day. Also the checks the page
// makes before the server's (which checks every field again) and the progress line of a
// season being built.
import { h, field, numberInput, checkbox } from './ui.js';

/**
 * Lines of "age grams" (or "age, grams") as fertilisations [[age, grams], ...]; throws naming
 * the line that is not two numbers, an age below 0 or grams not above 0.
 */
export function parseFertilise(text) {
  const events = [];
  text.split('\n').forEach((line, i) => {
    const t = line.trim();
    if (!t) return;
    const v = t.split(/[\s,]+/).map(Number);
    if (v.length !== 2 || v.some((x) => !Number.isFinite(x)))
      throw new Error(`fertilisation, line ${i + 1}: '${t}' is not two numbers: age grams`);
    if (v[0] < 0 || v[0] > 100000)
      throw new Error(`fertilisation, line ${i + 1}: age ${v[0]} (valid: 0 to 100000 days)`);
    if (!(v[1] > 0) || v[1] > 1e6)
      throw new Error(`fertilisation, line ${i + 1}: ${v[1]} g (valid: above 0, at most 10^6)`);
    events.push(v);
  });
  return events;
}

/** Whether `text` is a real date "YYYY-MM-DD" from 1900 to 2100. */
export function isDate(text) {
  const m = /^(\d{4})-(\d{2})-(\d{2})$/.exec(text ?? '');
  if (!m) return false;
  const [y, mo, d] = m.slice(1).map(Number);
  const date = new Date(Date.UTC(y, mo - 1, d));
  return (
    y >= 1900 &&
    y <= 2100 &&
    date.getUTCFullYear() === y &&
    date.getUTCMonth() === mo - 1 &&
    date.getUTCDate() === d
  );
}

/**
 * What is wrong with the editor's project's physiology, as messages naming the field (none
 * when it is off or fine): no model on, a fertilisation without the nitrogen model, a start
 * that is not a date, a block younger than the season.
 */
export function physiologyProblems(p) {
  const s = p.physiology;
  if (!s?.enabled) return [];
  const problems = [];
  if (!s.carbon && !s.nitrogen)
    problems.push('switch on the carbohydrate budget, the nitrogen model or both');
  if (s.fertilise.length && !s.nitrogen)
    problems.push('fertilisation needs the nitrogen model');
  if (!s.weather && !isDate(s.start))
    problems.push(`start '${s.start}': not a date YYYY-MM-DD from 1900 to 2100`);
  for (const b of p.blocks)
    if (b.age < s.days)
      problems.push(
        `block ${b.name} is ${b.age} days old: every block must be at least ${s.days} days (the season) old`,
      );
  return problems;
}

/** The progress line of a running build: its stage and share done; a season counts days. */
export function progressText(stage, progress, project) {
  const share = `${Math.round((progress ?? 0) * 100)}%`;
  if (stage === 'physiology' && project?.physiology) {
    const days = project.physiology.days;
    const day = Math.min(days, Math.floor((progress ?? 0) * days) + 1);
    return `Physiology season: day ${day} of ${days}… ${share}`;
  }
  const name = stage ? stage.charAt(0).toUpperCase() + stage.slice(1) : 'Queued';
  return `${name}… ${share}`;
}

/** The physiology section of the Environment tab, editing `app.project.physiology`. */
export function physiologySection(app) {
  const s = app.project.physiology;
  const problems = h('div', { class: 'error-text', id: 'physiology-problems', hidden: true });
  const showProblems = () => {
    const list = physiologyProblems(app.project);
    problems.hidden = !list.length;
    problems.replaceChildren(...list.map((m) => h('p', {}, m)));
  };
  app.checkPhysiology = showProblems; // after every edit, a block's age too
  const edited = () => app.edited();
  const set = (key) => (v) => {
    s[key] = v;
    edited();
  };
  const place = (index) => (v) => {
    s.location[index] = v;
    edited();
  };

  const start = h('input', { type: 'date', name: 'physiology-start', value: s.start });
  start.addEventListener('change', () => {
    s.start = start.value;
    edited();
  });
  const weather = h('input', {
    type: 'text',
    name: 'physiology-weather',
    value: s.weather,
    placeholder: 'weather.csv (empty: clear days)',
  });
  weather.addEventListener('change', () => {
    s.weather = weather.value.trim();
    start.disabled = !!s.weather;
    edited();
  });
  start.disabled = !!s.weather;

  const fertilise = h(
    'textarea',
    { rows: 2, name: 'physiology-fertilise', placeholder: '20 0.5\n35 0.5', spellcheck: false },
    s.fertilise.map((e) => e.join(' ')).join('\n'),
  );
  const fertiliseError = h('p', { class: 'error-text', hidden: true });
  fertilise.addEventListener('change', () => {
    try {
      s.fertilise = parseFertilise(fertilise.value);
      fertiliseError.hidden = true;
      edited();
    } catch (e) {
      fertiliseError.textContent = e.message;
      fertiliseError.hidden = false;
    }
  });

  const body = h(
    'div',
    { class: 'physiology-body', hidden: !s.enabled },
    seasonFields(s, set, place, start),
    field('Weather file (CSV)', weather, {
      wide: true,
      title: 'hourly weather, relative to the output folder; it replaces the clear days',
    }),
    field('Fertilisation: age (days) and grams N a plant, one per line', fertilise, {
      wide: true,
      title: 'needs the nitrogen model',
    }),
    fertiliseError,
  );
  showProblems();
  return h(
    'section',
    { class: 'group', id: 'physiology' },
    h(
      'h2',
      {},
      h(
        'label',
        { class: 'toggle' },
        checkbox(
          s.enabled,
          (v) => {
            s.enabled = v;
            body.hidden = !v;
            edited();
          },
          { name: 'physiology' },
        ),
        'Physiology season',
      ),
    ),
    h(
      'p',
      { class: 'hint' },
      'The last days of growth run the carbohydrate budget and/or the nitrogen model, the light traced through the scene each day. Slow: a season is built afresh at every change. Colour by light or carbon to see the result.',
    ),
    body,
    problems,
  );
}

// The grid of the season's models, place, dates and light: `set(key)` and `place(index)`
// make each field's setter; `start` is the date input (disabled by a weather file).
function seasonFields(s, set, place, start) {
  return h(
    'div',
    { class: 'grid2' },
    field('Carbon', checkbox(s.carbon, set('carbon'), { name: 'physiology-carbon' }), {
      title: 'the carbohydrate budget: photosynthesis pays for growth, sugar and starch kept',
    }),
    field('Nitrogen', checkbox(s.nitrogen, set('nitrogen'), { name: 'physiology-nitrogen' }), {
      title: 'the nitrogen model: leaf nitrogen sets photosynthesis, fertiliser adds to it',
    }),
    field(
      'Latitude',
      numberInput(s.location[0], place(0), { min: -90, max: 90, step: 0.01, name: 'latitude' }),
      { unit: '°', title: 'north positive, -90 to 90' },
    ),
    field(
      'Longitude',
      numberInput(s.location[1], place(1), {
        min: -180,
        max: 180,
        step: 0.01,
        name: 'longitude',
      }),
      { unit: '°', title: 'east positive, -180 to 180' },
    ),
    field('Start', start, { title: 'the first of the clear days (UTC date)' }),
    field(
      'Days',
      numberInput(s.days, set('days'), { min: 1, max: 100000, integer: true, name: 'days' }),
      { title: 'the last days of growth, with the models; every block at least this old' },
    ),
    field(
      'Light every',
      numberInput(s.light_every, set('light_every'), {
        min: 1,
        max: 24,
        integer: true,
        name: 'light-every',
      }),
      {
        unit: 'h',
        title: 'hours of daylight between traces of the light, 1 to 24: more is faster',
      },
    ),
    field(
      'Clearness',
      numberInput(s.clearness, set('clearness'), {
        min: 0,
        max: 1,
        step: 0.05,
        name: 'clearness',
      }),
      { title: 'of the clear days: 0 overcast, 1 a perfectly clear sky' },
    ),
  );
}
