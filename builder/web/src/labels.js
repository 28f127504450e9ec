// The labels of plantarch's GLB files and the colours the viewer gives them. Every mesh
// primitive carries per-vertex _PLANT_ID, _ORGAN and _FEATURE_ID_0 attributes (three.js names
// them in lower case); the feature ID is the row of the EXT_structural_metadata property
// table that holds each organ object's plant, organ, leaf, shoot, rank and age.
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
 * columns: {plant, organ, leaf, shoot, rank, age: typed arrays}}, or null without one.
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
  for (const [name, prop] of Object.entries(table.properties)) {
    const def = cls?.properties?.[name];
    const type =
      def?.type === 'ENUM'
        ? (ext.schema.enums[def.enumType].valueType ?? 'UINT16')
        : def?.componentType;
    const Array_ = COMPONENT_ARRAYS[type];
    if (!Array_) continue;
    const buffer = await gltf.parser.getDependency('bufferView', prop.values);
    columns[name] = new Array_(buffer, 0, table.count);
  }
  return { count: table.count, organNames, columns };
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

// A perceptually even ramp (dark blue, teal, green, yellow) for ages.
const RAMP = [
  [68, 1, 84],
  [59, 82, 139],
  [33, 145, 140],
  [94, 201, 98],
  [253, 231, 37],
];
export function rampColor(t) {
  const x = Math.max(0, Math.min(1, t)) * (RAMP.length - 1);
  const i = Math.min(RAMP.length - 2, Math.floor(x));
  const f = x - i;
  return RAMP[i].map((c, k) => c + (RAMP[i + 1][k] - c) * f);
}

export const COLOR_MODES = [
  ['natural', 'Natural'],
  ['organ', 'Organ'],
  ['plant', 'Plant'],
  ['leaf', 'Leaf'],
  ['age', 'Age'],
  ['rank', 'Shoot rank'],
];

/**
 * The colour function of a mode over the property table: row -> [r, g, b] (0-255), and the
 * legend entries [{label, color}] or a ramp {min, max}.
 */
export function colorScheme(mode, table) {
  const c = table.columns;
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
    ramp: { min, max, unit: 'days' },
  };
}
