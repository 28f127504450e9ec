// The project as the builder edits it, and its file form (builder/API.md, "project file",
// version 1). The editor keeps every field of a block whatever its layout (switching layout
// back and forth loses nothing); toProjectFile writes only the fields of the block's layout.
// A project file's defaults come from the server (defaults.js), which has them from
// plantarch's own declarations; only the editor's starting values below are the page's.
import { defaults } from './defaults.js';

export const PROJECT_VERSION = 1;

// The editor's starting values, which are not a project file's defaults: a new project's
// name, and a new block's size (a 3 x 3 grid, or 12 positions over 1.5 m x 1.5 m) and age.
// The editor also gives that age to a block whose file has none (which the command line
// builds at the species' recommended age): it holds no "none" for an age.
const NEW_PROJECT_NAME = 'untitled';
const NEW_BLOCK = { count: [3, 3], plants: 12, area: [1.5, 1.5], age: 40 };
// A physiology season as the editor starts it (off), where a file's defaults would not build:
// the carbohydrate budget on, a place and a first clear day, and a short season traced every
// 4 hours, quick enough to build after each change.
const NEW_PHYSIOLOGY = {
  enabled: false,
  carbon: true,
  location: [38.54, -121.74],
  start: '2026-06-01',
  light_every: 4,
  days: 10,
};

// A block as a project file that omits every optional field gives it.
function fileBlock(index, species) {
  const { grid, scatter, skeleton } = defaults().blocks;
  return {
    name: blockName(index),
    species,
    layout: grid.layout,
    origin: [...grid.origin],
    count: [...grid.count], // grid: plants along x and y
    spacing: [...grid.spacing], // grid: m
    plants: scatter.count, // scatter: positions drawn
    area: [...scatter.area], // scatter: m
    germination: grid.germination,
    age: NEW_BLOCK.age,
    seed: grid.seed ?? null, // null: the project's seed
    parameters: { ...grid.parameters },
    // species file fields changed for this block (plantarch fit's paths), kept as read
    species_parameters: { ...(grid.species_parameters ?? {}) },
    trellis: grid.trellis,
    // skeleton: a measured skeleton file (relative to OUTPUT/projects/), its unit and spacing
    skeleton: { ...skeleton.skeleton },
    bend: grid.bend, // the plants bend under their load
    elastic_modulus: grid.elastic_modulus ?? null, // Pa; null: the species'
  };
}

/** A new block of the editor: the file's defaults with the editor's starting size and age. */
export function defaultBlock(index = 0, species = 'bean') {
  return { ...fileBlock(index, species), ...structuredClone(NEW_BLOCK) };
}

function ground(enabled, size, center) {
  const d = defaults().ground;
  return { enabled, size: [...(size ?? d.size)], center: [...(center ?? d.center)] };
}

// The editor's season: the file's defaults (the server's) under the editor's starting values.
// `weather` is '' for clear days from `start`.
function defaultPhysiology() {
  const f = defaults().physiology;
  return {
    ...NEW_PHYSIOLOGY,
    nitrogen: f.nitrogen,
    location: [...NEW_PHYSIOLOGY.location],
    weather: f.weather ?? '',
    clearness: f.clearness,
    fertilise: f.fertilise.map((e) => [...e]),
  };
}

/** "A", "B", ... "Z", "AA", ... */
export function blockName(index) {
  let name = '';
  for (let i = index + 1; i > 0; i = Math.floor((i - 1) / 26))
    name = String.fromCharCode(65 + ((i - 1) % 26)) + name;
  return name;
}

export function defaultProject() {
  const f = defaults().project;
  return {
    name: NEW_PROJECT_NAME,
    seed: f.seed,
    mesh_detail: f.mesh_detail,
    // No ground by default, as `plantarch canopy`: the view draws a grid, the renderer its own
    // floor.
    ground: ground(f.ground !== null, f.ground?.size, f.ground?.center),
    soft_collision: { enabled: f.soft_collision.enabled, cone: [...f.soft_collision.cone] },
    obstacles: {
      files: [...f.obstacles.files],
      avoid_distance: f.obstacles.avoid_distance,
      fruit_adjustment: f.obstacles.fruit_adjustment,
    },
    attraction: {
      enabled: f.attraction.enabled,
      points: f.attraction.points.map((q) => [...q]),
      file: f.attraction.file ?? '',
      cone: [...f.attraction.cone],
    },
    blocks: [defaultBlock(0)],
    physiology: defaultPhysiology(),
  };
}

/** The project file (JSON value) of the editor's project. */
export function toProjectFile(p) {
  const out = {
    plantarch_project: PROJECT_VERSION,
    name: p.name,
    seed: p.seed,
    mesh_detail: p.mesh_detail,
  };
  out.ground = p.ground.enabled ? { size: [...p.ground.size], center: [...p.ground.center] } : null;
  out.soft_collision = { enabled: p.soft_collision.enabled, cone: [...p.soft_collision.cone] };
  out.obstacles = {
    files: [...p.obstacles.files],
    avoid_distance: p.obstacles.avoid_distance,
    fruit_adjustment: p.obstacles.fruit_adjustment,
  };
  out.attraction = {
    enabled: p.attraction.enabled,
    points: p.attraction.points.map((q) => [...q]),
    file: p.attraction.file ? p.attraction.file : null,
    cone: [...p.attraction.cone],
  };
  out.blocks = p.blocks.map(blockToFile);
  if (p.physiology.enabled) out.physiology = physiologyToFile(p.physiology);
  return out;
}

function physiologyToFile(s) {
  return {
    carbon: s.carbon,
    nitrogen: s.nitrogen,
    location: [...s.location],
    start: s.weather ? null : s.start,
    weather: s.weather ? s.weather : null,
    clearness: s.clearness,
    light_every: s.light_every,
    days: s.days,
    fertilise: s.fertilise.map((e) => [...e]),
  };
}

// The editor's season from a file's `physiology` (switched on); what the file omits keeps
// the editor's value.
function physiologyFromFile(json) {
  if (typeof json !== 'object' || Array.isArray(json))
    throw new Error('physiology: not an object {carbon, nitrogen, location, ...}');
  const s = { ...defaultPhysiology(), enabled: true };
  for (const key of ['carbon', 'nitrogen']) if (json[key] !== undefined) s[key] = !!json[key];
  if (json.location !== undefined) {
    if (!Array.isArray(json.location) || json.location.length !== 2)
      throw new Error('physiology/location: not [latitude, longitude]');
    s.location = [...json.location];
  }
  if (typeof json.start === 'string') s.start = json.start;
  s.weather = typeof json.weather === 'string' ? json.weather : '';
  for (const key of ['clearness', 'light_every', 'days'])
    if (Number.isFinite(json[key])) s[key] = json[key];
  if (json.fertilise !== undefined) {
    if (!Array.isArray(json.fertilise) || json.fertilise.some((e) => !Array.isArray(e)))
      throw new Error('physiology/fertilise: not a list of [age, grams]');
    s.fertilise = json.fertilise.map((e) => [...e]);
  }
  return s;
}

function blockToFile(b) {
  const out = { name: b.name, species: b.species, layout: b.layout, origin: [...b.origin] };
  if (b.layout === 'grid') {
    out.count = [...b.count];
    out.spacing = [...b.spacing];
  } else if (b.layout === 'scatter') {
    out.area = [...b.area];
    out.count = b.plants;
  } else if (b.layout === 'skeleton') {
    out.skeleton = { ...b.skeleton };
  }
  if (b.layout === 'grid' || b.layout === 'scatter') out.germination = b.germination;
  out.age = b.age;
  if (b.seed !== null && b.seed !== undefined) out.seed = b.seed;
  if (b.layout !== 'skeleton') {
    if (Object.keys(b.parameters).length) out.parameters = { ...b.parameters };
    out.trellis = b.trellis;
  }
  if (Object.keys(b.species_parameters ?? {}).length)
    out.species_parameters = { ...b.species_parameters };
  out.bend = !!b.bend;
  out.elastic_modulus = b.elastic_modulus ?? null;
  return out;
}

/**
 * The editor's project from a project file's JSON value. Throws an Error naming the field for
 * what the editor cannot hold; the server checks everything else when the project is built.
 */
export function fromProjectFile(json) {
  if (typeof json !== 'object' || json === null || Array.isArray(json))
    throw new Error('the project file is not a JSON object');
  if (json.plantarch_project !== PROJECT_VERSION) {
    throw new Error(
      `plantarch_project = ${JSON.stringify(json.plantarch_project)}: not a plantarch project file of version ${PROJECT_VERSION}`,
    );
  }
  const p = defaultProject();
  if (typeof json.name === 'string') p.name = json.name;
  if (Number.isFinite(json.seed)) p.seed = json.seed;
  if (Number.isFinite(json.mesh_detail)) p.mesh_detail = json.mesh_detail;
  p.ground = json.ground ? ground(true, json.ground.size, json.ground.center) : ground(false);
  if (json.soft_collision) {
    p.soft_collision = {
      enabled: !!json.soft_collision.enabled,
      cone: [...(json.soft_collision.cone ?? p.soft_collision.cone)],
    };
  }
  if (json.obstacles) {
    p.obstacles = {
      files: [...(json.obstacles.files ?? [])],
      avoid_distance: json.obstacles.avoid_distance ?? p.obstacles.avoid_distance,
      fruit_adjustment: !!json.obstacles.fruit_adjustment,
    };
  }
  if (json.attraction) {
    p.attraction = {
      enabled: !!json.attraction.enabled,
      points: (json.attraction.points ?? []).map((q) => [...q]),
      file: json.attraction.file ?? '',
      cone: [...(json.attraction.cone ?? p.attraction.cone)],
    };
  }
  if (!Array.isArray(json.blocks)) throw new Error('blocks: missing (a list of blocks)');
  p.blocks = json.blocks.map((b, i) => blockFromFile(b, i));
  if (json.physiology !== undefined && json.physiology !== null)
    p.physiology = physiologyFromFile(json.physiology);
  return p;
}

// The fields of the block's own layout that the file omits take the file format's defaults;
// the other layouts' fields (used if the layout is switched) the editor's starting values.
function blockFromFile(b, i) {
  const block = defaultBlock(i, b.species);
  const file = fileBlock(i, b.species);
  if ((b.layout ?? file.layout) === 'grid') Object.assign(block, { count: file.count });
  if (b.layout === 'scatter') Object.assign(block, { plants: file.plants, area: file.area });
  for (const key of ['name', 'species', 'layout', 'germination', 'age', 'trellis', 'bend']) {
    if (b[key] !== undefined) block[key] = b[key];
  }
  if (Array.isArray(b.origin)) block.origin = [...b.origin];
  if (b.seed !== undefined) block.seed = b.seed;
  if (b.parameters) block.parameters = { ...b.parameters };
  if (b.species_parameters && typeof b.species_parameters === 'object')
    block.species_parameters = { ...b.species_parameters };
  if (Number.isFinite(b.elastic_modulus)) block.elastic_modulus = b.elastic_modulus;
  if (b.skeleton && typeof b.skeleton === 'object')
    block.skeleton = { ...block.skeleton, ...b.skeleton };
  if (block.layout === 'grid') {
    if (Array.isArray(b.count)) block.count = [...b.count];
    if (Array.isArray(b.spacing)) block.spacing = [...b.spacing];
  } else if (block.layout === 'scatter') {
    if (Number.isFinite(b.count)) block.plants = b.count;
    if (Array.isArray(b.area)) block.area = [...b.area];
  }
  return block;
}

/** A copy of block `b` named after `index` (Duplicate). */
export function duplicateBlock(b, index) {
  return { ...structuredClone(b), name: blockName(index) };
}

/** The number of plant positions of a block (before germination). */
export function positions(b) {
  if (b.layout === 'grid') return b.count[0] * b.count[1];
  if (b.layout === 'scatter') return b.plants;
  return 1;
}
