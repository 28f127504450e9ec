// Unit tests of the page's pure functions (node's test runner; ctest runs them as
// builder_web_unit, with PLANTARCH_CLI the plantarch binary): the project file the page writes
// and reads (a physiology season too), random-value text, typed attraction points and
// fertilisations, the label colours (light and carbon too), and the defaults the page takes
// from its server (GET /api/defaults of `plantarch builder`, started here).
import test from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { setDefaults } from '../src/defaults.js';
import {
  blockName,
  defaultBlock,
  defaultProject,
  fromProjectFile,
  toProjectFile,
} from '../src/project.js';
import { parseRandom, randomText } from '../src/species_editor.js';
import { parsePoints } from '../src/environment_panel.js';
import {
  AGE_RAMP,
  CARBON_RAMP,
  LIGHT_RAMP,
  colorScheme,
  modeUnavailable,
  organColors,
  rampColor,
} from '../src/labels.js';
import {
  isDate,
  parseFertilise,
  physiologyProblems,
  progressText,
} from '../src/physiology_panel.js';
import { formatOptions } from '../src/export_panel.js';
import { runText, PREVIEW_PICTURES } from '../src/dataset_panel.js';

// GET /api/defaults of a `plantarch builder` started for it on a free port.
async function servedDefaults() {
  const cli = process.env.PLANTARCH_CLI;
  if (!cli) throw new Error('PLANTARCH_CLI (the plantarch binary) is not set');
  const probe = net.createServer();
  await new Promise((resolve) => probe.listen(0, '127.0.0.1', resolve));
  const { port } = probe.address();
  await new Promise((resolve) => probe.close(resolve));
  const tmp = mkdtempSync(path.join(os.tmpdir(), 'plantarch-web-unit-'));
  const server = spawn(cli, ['builder', '--port', String(port), '--output', tmp], {
    stdio: 'ignore',
  });
  try {
    for (let i = 0; i < 600; i++) {
      if (server.exitCode !== null) throw new Error(`plantarch builder exited (${server.exitCode})`);
      try {
        const response = await fetch(`http://127.0.0.1:${port}/api/defaults`);
        if (response.ok) return await response.json();
      } catch {
        // not listening yet
      }
      await new Promise((resolve) => setTimeout(resolve, 50));
    }
    throw new Error('plantarch builder did not answer GET /api/defaults');
  } finally {
    server.kill();
    rmSync(tmp, { recursive: true, force: true });
  }
}

const served = await servedDefaults();
setDefaults(served);

// The three layouts of builder/API.md's example project.
function exampleProject() {
  const p = defaultProject();
  p.name = 'bean trial';
  p.blocks = [defaultBlock(0, 'bean'), defaultBlock(1, 'tomato'), defaultBlock(2, 'my_bean.xml')];
  Object.assign(p.blocks[1], {
    layout: 'scatter',
    origin: [2, 0, 0],
    area: [1.5, 1.5],
    plants: 12,
    age: 30,
    seed: 7,
  });
  Object.assign(p.blocks[2], { layout: 'single', origin: [0, 2, 0], age: 20 });
  p.blocks[0].parameters = { trunk_height: 0.6 };
  return p;
}

test('a grid block is written with count [x, y] and spacing, and nothing of other layouts', () => {
  const file = toProjectFile(defaultProject());
  assert.equal(file.plantarch_project, 1);
  assert.deepEqual(file.blocks[0], {
    name: 'A',
    species: 'bean',
    layout: 'grid',
    origin: [0, 0, 0],
    count: [3, 3],
    spacing: [0.3, 0.3],
    germination: 1,
    age: 40,
    trellis: true,
    bend: false,
    elastic_modulus: null,
  });
  assert.equal(file.ground, null);
  const withGround = defaultProject();
  withGround.ground.enabled = true;
  assert.deepEqual(toProjectFile(withGround).ground, { size: [4, 4], center: [0, 0] });
});

test('a scatter block is written with count as a number and its area; a single plant with neither', () => {
  const [, scatter, single] = toProjectFile(exampleProject()).blocks;
  assert.equal(scatter.count, 12);
  assert.deepEqual(scatter.area, [1.5, 1.5]);
  assert.equal(scatter.seed, 7);
  assert.ok(!('spacing' in scatter) && !('plants' in scatter));
  for (const key of ['count', 'spacing', 'area', 'germination', 'parameters'])
    assert.ok(!(key in single), key);
});

test('a skeleton block is written with its file, unit and spacing, bent or not', () => {
  const p = defaultProject();
  Object.assign(p.blocks[0], {
    layout: 'skeleton',
    skeleton: { file: '../skeletons/pepper.csv', unit: 0.01, spacing: 0 },
    bend: true,
    elastic_modulus: 2e9,
  });
  const [block] = toProjectFile(p).blocks;
  assert.deepEqual(block.skeleton, { file: '../skeletons/pepper.csv', unit: 0.01, spacing: 0 });
  assert.equal(block.bend, true);
  assert.equal(block.elastic_modulus, 2e9);
  for (const key of ['count', 'spacing', 'area', 'germination', 'parameters', 'trellis'])
    assert.ok(!(key in block), key);
  const file = toProjectFile(p);
  assert.deepEqual(toProjectFile(fromProjectFile(JSON.parse(JSON.stringify(file)))), file);
});

test('a project file read back writes the same file', () => {
  const file = toProjectFile(exampleProject());
  assert.deepEqual(toProjectFile(fromProjectFile(JSON.parse(JSON.stringify(file)))), file);
  const noGround = { ...file, ground: null };
  assert.equal(toProjectFile(fromProjectFile(noGround)).ground, null);
});

test('a file of another format is refused naming the field', () => {
  assert.throws(() => fromProjectFile({ blocks: [] }), /plantarch_project/);
  assert.throws(
    () => fromProjectFile({ plantarch_project: 2, blocks: [] }),
    /plantarch_project = 2/,
  );
  assert.throws(() => fromProjectFile({ plantarch_project: 1 }), /blocks/);
  assert.throws(() => fromProjectFile([1]), /not a JSON object/);
});

test('block names run A to Z, then AA', () => {
  assert.deepEqual([0, 1, 25, 26, 27, 701, 702].map(blockName), [
    'A',
    'B',
    'Z',
    'AA',
    'AB',
    'ZZ',
    'AAA',
  ]);
});

test('random values split into a distribution and its arguments, and back', () => {
  assert.deepEqual(parseRandom('uniform(40, 60)'), { kind: 'uniform', args: ['40', '60'] });
  assert.deepEqual(parseRandom(' normal(0,20) '), { kind: 'normal', args: ['0', '20'] });
  assert.deepEqual(parseRandom('0.025'), { kind: 'constant', args: ['0.025'] });
  assert.equal(randomText('weibull', ['1.5', '2']), 'weibull(1.5, 2)');
  assert.equal(randomText('constant', ['3']), '3');
  for (const text of ['uniform(1, 4)', 'discrete(2, 5, 11)', 'normal(0, 5)', '7']) {
    const { kind, args } = parseRandom(text);
    assert.equal(randomText(kind, args), text);
  }
});

test('attraction points: three numbers a line; a bad line is named', () => {
  assert.deepEqual(parsePoints('0 0 1.2\n\n0.5, 0, 1.2\n'), [
    [0, 0, 1.2],
    [0.5, 0, 1.2],
  ]);
  assert.throws(() => parsePoints('0 0 1\n1 2'), /line 2: '1 2'/);
  assert.throws(() => parsePoints('a b c'), /line 1/);
});

test("organ colours are the label images' colours; ages run over the organs' range", () => {
  const table = {
    count: 3,
    organNames: ['unlabelled', 'internode', 'petiole', 'leaf'],
    columns: {
      plant: Int32Array.from([0, 0, 1]),
      organ: Uint8Array.from([1, 3, 3]),
      leaf: Int32Array.from([-1, 0, 0]),
      rank: Int32Array.from([0, 0, 1]),
      age: Float32Array.from([10, 4, -1]),
    },
  };
  const organ = colorScheme('organ', table);
  assert.deepEqual(organ.color(1), organColors().leaf);
  assert.deepEqual(
    organ.legend.map((e) => e.label),
    ['internode', 'leaf'],
  );
  const age = colorScheme('age', table);
  assert.deepEqual(age.ramp, { min: 4, max: 10, unit: 'days', label: 'organ age', stops: AGE_RAMP });
  assert.notDeepEqual(age.color(0), age.color(1));
  const plant = colorScheme('plant', table);
  assert.notDeepEqual(plant.color(0), plant.color(2));
  assert.deepEqual(colorScheme('leaf', table).color(0), [150, 150, 150], 'not a leaf: grey');
  const rank = colorScheme('rank', table);
  assert.notDeepEqual(rank.color(0), rank.color(2));
  assert.deepEqual(
    rank.legend.map((e) => e.label),
    ['rank 0 (base stem)', 'rank 1', 'no shoot'],
  );
});

test("the page's defaults are the server's: project, ground, blocks, colours, formats", () => {
  const p = defaultProject();
  const file = toProjectFile(p);
  // Every project-wide field but the editor's name is the served project file's.
  for (const key of ['seed', 'mesh_detail', 'ground', 'soft_collision', 'obstacles', 'attraction'])
    assert.deepEqual(file[key], served.project[key], key);
  p.ground.enabled = true;
  assert.deepEqual(toProjectFile(p).ground, served.ground);
  // A block that gives only its species and layout reads as the served block of its layout.
  for (const [layout, block] of Object.entries(served.blocks)) {
    const read = fromProjectFile({
      plantarch_project: 1,
      blocks: [{ species: 'bean', layout, age: 40 }],
    });
    const written = toProjectFile(read).blocks[0];
    // (The page writes no empty parameters or species parameters; the served block holds
    // none; a skeleton block has no build parameters at all.)
    assert.deepEqual(block.parameters ?? {}, {});
    assert.deepEqual(block.species_parameters ?? {}, {});
    const unwritten = ['name', 'age', 'parameters', 'species_parameters'];
    for (const key of Object.keys(block).filter((k) => !unwritten.includes(k)))
      assert.deepEqual(written[key], block[key], `${layout}: ${key}`);
  }
  assert.deepEqual(organColors(), served.organ_colors);
  assert.ok(organColors().leaf && organColors().unlabelled);
  assert.deepEqual(
    formatOptions().map(([format]) => format),
    served.export_formats.map((f) => f.format),
  );
});

test("the served season's defaults are the page's, under its own place, date and model", () => {
  const s = defaultProject().physiology;
  assert.equal(s.enabled, false);
  assert.equal(s.carbon, true, 'a season needs a model: the page starts with the budget on');
  assert.equal(s.nitrogen, served.physiology.nitrogen);
  assert.equal(s.clearness, served.physiology.clearness);
  assert.deepEqual(s.fertilise, served.physiology.fertilise);
  assert.equal(s.weather, '');
  assert.ok(isDate(s.start));
  assert.ok(!('physiology' in toProjectFile(defaultProject())), 'off: no section written');
});

test('a physiology season is written after the blocks, read back the same, clear days or weather', () => {
  const p = defaultProject();
  p.blocks[0].age = 22;
  Object.assign(p.physiology, {
    enabled: true,
    nitrogen: true,
    location: [52.2, 0.12],
    start: '2026-05-03',
    light_every: 6,
    days: 2,
    fertilise: [[20, 0.5]],
  });
  const file = toProjectFile(p);
  assert.deepEqual(Object.keys(file).slice(-2), ['blocks', 'physiology']);
  assert.deepEqual(file.physiology, {
    carbon: true,
    nitrogen: true,
    location: [52.2, 0.12],
    start: '2026-05-03',
    weather: null,
    clearness: served.physiology.clearness,
    light_every: 6,
    days: 2,
    fertilise: [[20, 0.5]],
  });
  assert.deepEqual(toProjectFile(fromProjectFile(JSON.parse(JSON.stringify(file)))), file);
  p.physiology.weather = 'davis.csv';
  const weathered = toProjectFile(p).physiology;
  assert.equal(weathered.start, null);
  assert.equal(weathered.weather, 'davis.csv');
  assert.deepEqual(toProjectFile(fromProjectFile(toProjectFile(p))).physiology, weathered);
  // The example project of the repository reads in and writes the same season.
  const example = JSON.parse(
    readFileSync(new URL('../../../examples/projects/season.json', import.meta.url), 'utf8'),
  );
  assert.deepEqual(toProjectFile(fromProjectFile(example)).physiology, {
    weather: null,
    ...example.physiology,
  });
  assert.throws(
    () => fromProjectFile({ ...example, physiology: { location: 5 } }),
    /physiology\/location/,
  );
});

test('fertilisations: two numbers a line, in range; the page names what the server would refuse', () => {
  assert.deepEqual(parseFertilise('20 0.5\n\n35, 1\n'), [
    [20, 0.5],
    [35, 1],
  ]);
  assert.throws(() => parseFertilise('20'), /line 1: '20' is not two numbers/);
  assert.throws(() => parseFertilise('20 1\n-1 2'), /line 2: age -1/);
  assert.throws(() => parseFertilise('20 0'), /0 g/);
  assert.ok(isDate('2024-02-29') && !isDate('2023-02-29') && !isDate('2026-6-1'));
  assert.ok(!isDate('1899-12-31') && isDate('2100-12-31'));

  const p = defaultProject();
  assert.deepEqual(physiologyProblems(p), [], 'off: nothing to say');
  p.physiology.enabled = true;
  p.blocks[0].age = 22;
  p.physiology.days = 2;
  assert.deepEqual(physiologyProblems(p), []);
  Object.assign(p.physiology, { carbon: false, fertilise: [[20, 1]], start: '2026-02-30' });
  p.physiology.days = 30;
  const problems = physiologyProblems(p).join('\n');
  assert.match(problems, /carbohydrate budget, the nitrogen model or both/);
  assert.match(problems, /fertilisation needs the nitrogen model/);
  assert.match(problems, /start '2026-02-30'/);
  assert.match(problems, /block A is 22 days old: .* at least 30 days/);
});

test('a season counts its days in the progress line; other stages show their name', () => {
  const project = { physiology: { days: 4 } };
  assert.equal(progressText('physiology', 0, project), 'Physiology season: day 1 of 4… 0%');
  assert.equal(progressText('physiology', 0.5, project), 'Physiology season: day 3 of 4… 50%');
  assert.equal(progressText('physiology', 1, project), 'Physiology season: day 4 of 4… 100%');
  assert.equal(progressText('building', 0.25, project), 'Building… 25%');
  assert.equal(progressText(undefined, undefined, {}), 'Queued… 0%');
});

test('light and carbon colour over the range of the objects with data; the others are grey', () => {
  const grey = [150, 150, 150];
  const table = {
    count: 4,
    organNames: ['unlabelled', 'internode', 'petiole', 'leaf'],
    columns: {
      plant: Int32Array.from([0, 0, 0, -1]),
      organ: Uint8Array.from([1, 3, 3, 0]),
      age: Float32Array.from([10, 4, 2, -1]),
      absorbed_par: Float32Array.from([-9999, 120, 480, -9999]),
      carbohydrate_concentration: Float32Array.from([0.1, 0.3, 0.3, -9999]),
    },
    noData: { absorbed_par: -9999, carbohydrate_concentration: -9999 },
  };
  const light = colorScheme('light', table);
  assert.deepEqual(light.ramp, {
    min: 120,
    max: 480,
    unit: 'µmol m⁻² s⁻¹',
    label: 'absorbed PAR',
    stops: LIGHT_RAMP,
  });
  assert.deepEqual(light.color(0), grey, 'an internode has no absorbed PAR');
  assert.deepEqual(light.color(3), grey);
  assert.deepEqual(light.color(1), LIGHT_RAMP[0]);
  assert.deepEqual(light.color(2), LIGHT_RAMP.at(-1));
  assert.deepEqual(light.legend, [{ label: 'no data', color: grey }]);
  const carbon = colorScheme('carbon', table);
  assert.equal(carbon.ramp.min.toFixed(6), '0.100000');
  assert.equal(carbon.ramp.max.toFixed(6), '0.300000');
  assert.equal(carbon.ramp.unit, 'mol C / mol C');
  assert.deepEqual(carbon.color(0), CARBON_RAMP[0]);
  assert.notDeepEqual(carbon.color(1), light.color(1), 'the two modes use different ramps');
  // The ramps run dark to light (each stop lighter), so order reads in grey too.
  for (const ramp of [LIGHT_RAMP, CARBON_RAMP]) {
    const luma = ramp.map(([r, g, b]) => 0.2126 * r + 0.7152 * g + 0.0722 * b);
    for (let i = 1; i < luma.length; i++) assert.ok(luma[i] > luma[i - 1], `stop ${i}`);
    assert.deepEqual(rampColor(0.5, ramp).length, 3);
  }
  // All values equal: one colour, no division by zero.
  const flat = {
    ...table,
    columns: { ...table.columns, absorbed_par: Float32Array.from([5, 5, 5, 5]) },
  };
  assert.deepEqual(colorScheme('light', flat).color(0), LIGHT_RAMP[0]);
  assert.deepEqual(colorScheme('light', flat).legend, []);

  // Without the columns (a scene built without a season) the modes are unavailable, saying why.
  const plain = { ...table, columns: { plant: table.columns.plant }, noData: {} };
  assert.match(modeUnavailable('light', plain), /no absorbed_par data: switch the physiology season on/);
  assert.match(modeUnavailable('carbon', plain), /no carbohydrate_concentration data: .* with Carbon/);
  assert.equal(modeUnavailable('light', table), null);
  assert.equal(modeUnavailable('age', plain), null);
  assert.equal(modeUnavailable('natural', null), null);
  assert.match(modeUnavailable('organ', null), /no labels/);
});

test("a dataset run's progress line: samples, rate, time left; the pictures a preview shows", () => {
  const running = { state: 'running', done: 12, total: 100, per_minute: 35.24, seconds_left: 3725 };
  assert.equal(runText(running), '12 / 100 samples · 35.2 per min · 1:02:05 left');
  assert.equal(runText({ ...running, seconds_left: 40 }), '12 / 100 samples · 35.2 per min · 0:40 left');
  assert.equal(runText({ ...running, per_minute: 0, seconds_left: null }), '12 / 100 samples');
  const done = { state: 'done', done: 2, total: 2, per_minute: 1200, bytes: 1.7e6, seconds: 0.1 };
  assert.equal(runText(done), '2 / 2 samples · 1,200 per min · 1.7 MB in 0.1 s');
  assert.match(runText({ ...running, state: 'cancelled' }), /cancelled$/);
  assert.deepEqual(
    PREVIEW_PICTURES.map(([key]) => key),
    ['rgb', 'semantic', 'instances', 'plants', 'depth'],
  );
});
