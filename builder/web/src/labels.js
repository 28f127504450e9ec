// The labels of plantarch's GLB files and the colours the viewer gives them. Every mesh
// primitive carries per-vertex _PLANT_ID, _ORGAN and _FEATURE_ID_0 attributes (three.js names
// them in lower case); the feature ID is the row of the EXT_structural_metadata property
// table that holds each organ object's plant, organ, leaf, shoot, rank and age, and, in a
// scene grown through a physiology season, its light and carbon columns (docs/formats.md).
import { defaults } from './defaults.js';

/** The organ label colours of plantarch's label images and colour-coded PLY files, by organ
 * name, as the server gives them. */
export function organColors() {
  return defaults().organ_colors;
}

const NONE = [150, 150, 150];

const COMPONENT_ARRAYS = {
  INT8: Int8Array,
  UINT8: Uint8Array,
  INT16: Int16Array,
  UINT16: Uint16Array,
  INT32: Int32Array,
  UINT32: Uint32Array,
  FLOAT32: Float32Array,
  FLOAT64: Float64Array,
};

/**
 * The property table of a loaded GLB (three.js GLTFLoader result): {count, organNames,
 * columns: {plant, organ, leaf, shoot, rank, age, ...: typed arrays}, noData: {column:
 * value}}, or null without one. Optional columns (absorbed_par, ...) are there when the file
 * has them; noData holds the schema's no-data value of the columns that declare one.
 */
export async function readPropertyTable(gltf) {
  const ext = gltf.parser.json.extensions?.EXT_structural_metadata;
  const table = ext?.propertyTables?.[0];
  if (!table) return null;
  const cls = ext.schema?.classes?.[table.class];
  const organEnum = ext.schema?.enums?.organ_kind?.values ?? [];
  const organNames = [];
  for (const v of organEnum) organNames[v.value] = v.name;
  const columns = {};
  const noData = {};
  for (const [name, prop] of Object.entries(table.properties)) {
    const def = cls?.properties?.[name];
    if (typeof def?.noData === 'number') noData[name] = def.noData;
    const type =
      def?.type === 'ENUM'
        ? (ext.schema.enums[def.enumType].valueType ?? 'UINT16')
        : def?.componentType;
    const Array_ = COMPONENT_ARRAYS[type];
    if (!Array_) continue;
    const buffer = await gltf.parser.getDependency('bufferView', prop.values);
    columns[name] = new Array_(buffer, 0, table.count);
  }
  return { count: table.count, organNames, columns, noData };
}

function hsl(h, s, l) {
  const a = s * Math.min(l, 1 - l);
  const f = (n) => {
    const k = (n + h * 12) % 12;
    return 255 * (l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1)));
  };
  return [f(0), f(8), f(4)];
}

/** A distinct colour for a whole number (golden-ratio hues). */
export function indexColor(i) {
  if (i < 0) return NONE;
  return hsl((i * 0.618033988749895 + 0.08) % 1, 0.62, 0.52);
}

// Perceptually even ramps, dark to light, as sRGB stops evenly spaced from 0 to 1 (each
// stop a little lighter than the one before, so order reads at a glance and in grey).
// AGE_RAMP and LIGHT_RAMP run dark blue, teal, green, yellow; CARBON_RAMP runs dark violet,
// red, orange, pale yellow, so the two physiology modes are not mistaken for each other.
export const AGE_RAMP = [
  [68, 1, 84],
  [59, 82, 139],
  [33, 145, 140],
  [94, 201, 98],
  [253, 231, 37],
];
export const LIGHT_RAMP = [
  [68, 1, 84],
  [72, 36, 117],
  [64, 68, 136],
  [52, 97, 141],
  [41, 122, 142],
  [32, 146, 140],
  [40, 171, 129],
  [81, 195, 105],
  [146, 214, 70],
  [218, 227, 38],
  [253, 231, 37],
];
export const CARBON_RAMP = [
  [18, 12, 50],
  [60, 15, 110],
  [110, 28, 120],
  [160, 44, 112],
  [205, 66, 90],
  [236, 104, 70],
  [249, 150, 80],
  [253, 196, 120],
  [252, 236, 176],
];

/** The colour at t (0 to 1, clamped) of a ramp of evenly spaced stops (AGE_RAMP by default). */
export function rampColor(t, stops = AGE_RAMP) {
  const x = Math.max(0, Math.min(1, Number.isFinite(t) ? t : 0)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const f = x - i;
  return stops[i].map((c, k) => c + (stops[i + 1][k] - c) * f);
}

/** A CSS linear-gradient of a ramp, left to right. */
export function rampGradient(stops) {
  return `linear-gradient(90deg, ${stops.map((c) => `rgb(${c.join(', ')})`).join(', ')})`;
}

// The colour modes of a property table column that only a physiology season writes: the
// column, what the legend calls it, its unit and ramp.
export const DATA_MODES = {
  light: {
    column: 'absorbed_par',
    label: 'absorbed PAR',
    unit: 'µmol m⁻² s⁻¹',
    stops: LIGHT_RAMP,
    needs: 'switch the physiology season on (Environment tab) and build',
  },
  carbon: {
    column: 'carbohydrate_concentration',
    label: 'carbohydrate concentration',
    unit: 'mol C / mol C',
    stops: CARBON_RAMP,
    needs: 'switch the physiology season on with Carbon (Environment tab) and build',
  },
};

/**
 * Why a colour mode cannot be used with a property table (null when it can): the physiology
 * modes need their column, which only a scene grown through a physiology season has.
 */
export function modeUnavailable(mode, table) {
  if (mode === 'natural') return null;
  if (!table) return 'the scene has no labels';
  const data = DATA_MODES[mode];
  if (data && !table.columns[data.column])
    return `the scene has no ${data.column} data: ${data.needs}`;
  return null;
}

export const COLOR_MODES = [
  ['natural', 'Natural'],
  ['organ', 'Organ'],
  ['plant', 'Plant'],
  ['leaf', 'Leaf'],
  ['age', 'Age'],
  ['rank', 'Shoot rank'],
  ['light', 'Light (absorbed PAR)'],
  ['carbon', 'Carbon (carbohydrate concentration)'],
];

/**
 * The colour function of a mode over the property table: row -> [r, g, b] (0-255), and the
 * legend entries [{label, color}] or a ramp {min, max}.
 */
export function colorScheme(mode, table) {
  const c = table.columns;
  if (DATA_MODES[mode]) return dataScheme(DATA_MODES[mode], table);
  if (mode === 'organ') {
    const colors = organColors();
    const used = new Set(c.organ);
    const name = (row) => table.organNames[c.organ[row]] ?? 'unlabelled';
    return {
      color: (row) => colors[name(row)] ?? NONE,
      legend: [...used]
        .sort((a, b) => a - b)
        .map((o) => ({
          label: (table.organNames[o] ?? 'unlabelled').replace('_', ' '),
          color: colors[table.organNames[o]] ?? NONE,
        })),
    };
  }
  if (mode === 'plant') {
    const plants = [...new Set(c.plant)].filter((p) => p >= 0).sort((a, b) => a - b);
    return {
      color: (row) => indexColor(c.plant[row]),
      legend: [
        { label: `${plants.length} plants, one colour each`, color: indexColor(plants[0] ?? 0) },
        { label: 'not a plant', color: NONE },
      ],
    };
  }
  if (mode === 'leaf') {
    return {
      color: (row) => (c.leaf[row] < 0 ? NONE : indexColor(c.leaf[row] * 7919 + c.plant[row] * 31)),
      legend: [
        { label: 'one colour per leaf', color: indexColor(3) },
        { label: 'not a leaf', color: NONE },
      ],
    };
  }
  if (mode === 'rank') {
    const ranks = [...new Set(c.rank)].filter((r) => r >= 0).sort((a, b) => a - b);
    return {
      color: (row) => indexColor(c.rank[row]),
      legend: [
        ...ranks.map((r) => ({
          label: r === 0 ? 'rank 0 (base stem)' : `rank ${r}`,
          color: indexColor(r),
        })),
        { label: 'no shoot', color: NONE },
      ],
    };
  }
  // age
  let min = Infinity,
    max = -Infinity;
  for (const a of c.age)
    if (a >= 0) {
      min = Math.min(min, a);
      max = Math.max(max, a);
    }
  if (!Number.isFinite(min)) {
    min = 0;
    max = 1;
  }
  const span = max - min || 1;
  return {
    color: (row) => (c.age[row] < 0 ? NONE : rampColor((c.age[row] - min) / span)),
    ramp: { min, max, unit: 'days', label: 'organ age', stops: AGE_RAMP },
  };
}

// A continuous column coloured over the range of the rows that have a value; rows at the
// column's noData (objects without the data), or without a finite value, are grey. The ramp
// is null when no row has a value.
function dataScheme(data, table) {
  const values = table.columns[data.column] ?? [];
  const noData = table.noData?.[data.column];
  const has = (v) => Number.isFinite(v) && v !== noData;
  let min = Infinity,
    max = -Infinity,
    missing = 0;
  for (const v of values) {
    if (!has(v)) {
      missing++;
      continue;
    }
    min = Math.min(min, v);
    max = Math.max(max, v);
  }
  const found = Number.isFinite(min);
  const span = max - min || 1;
  return {
    color: (row) =>
      has(values[row]) ? rampColor((values[row] - min) / span, data.stops) : NONE,
    ramp: found ? { min, max, unit: data.unit, label: data.label, stops: data.stops } : null,
    legend: missing || !found ? [{ label: 'no data', color: NONE }] : [],
  };
}
