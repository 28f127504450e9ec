// End-to-end test of `plantarch builder` in a real browser: Debian's Chromium (headless,
// driven by puppeteer-core) uses the page the way a person does, and every result the page
// shows is checked against the server's JSON API and the files on disk.
//
//   node builder_e2e.mjs --cli PATH/plantarch [--screenshots DIR]
//
// Scenario: the page loads; block A becomes a 3x3 grid of bean at 40 days and is built; the
// triangle count shown equals the API's (and the GLB's the view loaded); an invalid species
// parameter shows the species reader's own message, and an invalid block field the server's;
// the age slider grows the scene on (a build "from" the shown one, the same plants as built
// at that age anew) and the play button grows it day by day; GLB and per-plant OBJ exports
// are written and parse; a textured GLB with a node per organ is written from the page (the
// view showing the textured scene) and a refused variant shows the server's line; the saved
// project, uploaded into the page, builds the same scene, and its export is the file
// `plantarch project run` writes from the saved project, byte for byte;
// Cancel takes a queued build out and the API stops a running one; the API refuses paths outside the output folder and requests
// from other sites; colour by light or carbon is offered only for a scene with that data, and
// a physiology season switched on in the Environment tab is built afresh (never grown on), its
// scene coloured by absorbed PAR with a legend of its range; a measured skeleton (a file under
// the output folder) is rebuilt as a block of capsicum, a bad one refused with the server's
// line, and "Bend under load" bends a grown plant beside it; in the Dataset tab a spec is
// opened, its error shown, a sample previewed as pictures and 2 samples run into a dataset.
// With --screenshots, pictures of the page are written into DIR
// (docs/images for docs/builder.md). Waits are for states the page or the server reports,
// never for a time. CHROMIUM overrides /usr/bin/chromium.
import { spawn, execFileSync } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, readdirSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import assert from 'node:assert/strict';
import puppeteer from 'puppeteer-core';

function parseArgs(argv) {
  const options = { cli: null, screenshots: null };
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--cli') options.cli = path.resolve(argv[++i]);
    else if (argv[i] === '--screenshots') options.screenshots = path.resolve(argv[++i]);
    else throw new Error(`builder_e2e: unknown argument '${argv[i]}' (valid: --cli PATH, --screenshots DIR)`);
  }
  if (!options.cli) throw new Error('builder_e2e: --cli PATH (the plantarch binary) is required');
  return options;
}

const options = parseArgs(process.argv.slice(2));
if (options.screenshots) mkdirSync(options.screenshots, { recursive: true });
const tmp = mkdtempSync(path.join(os.tmpdir(), 'plantarch-builder-e2e-'));
const output = path.join(tmp, 'out');
let server = null;
let browser = null;
let serverLog = '';

function step(name) {
  console.log(`builder_e2e: ${name}`);
}

async function freePort() {
  const probe = net.createServer();
  await new Promise((resolve) => probe.listen(0, '127.0.0.1', resolve));
  const { port } = probe.address();
  await new Promise((resolve) => probe.close(resolve));
  return port;
}

// Starts the builder and resolves with its address once its API answers; rejects when the
// process ends first.
async function startServer() {
  const port = await freePort();
  server = spawn(options.cli, ['builder', '--port', String(port), '--output', output], { stdio: ['ignore', 'pipe', 'pipe'] });
  server.stdout.on('data', (d) => { serverLog += d; });
  server.stderr.on('data', (d) => { serverLog += d; });
  const exited = new Promise((_, reject) => server.on('exit', (code) =>
    reject(new Error(`plantarch builder exited (${code}) before answering:\n${serverLog}`))));
  const base = `http://127.0.0.1:${port}`;
  const ready = (async () => {
    for (;;) {
      try {
        const response = await fetch(`${base}/api/config`);
        if (response.ok) return base;
      } catch {
        // not listening yet
      }
      await new Promise((resolve) => setTimeout(resolve, 50));
    }
  })();
  return Promise.race([ready, exited]);
}

async function api(base, method, url, body, headers = {}) {
  const init = { method, headers: { ...headers } };
  if (body !== undefined) {
    init.headers['Content-Type'] = 'application/json';
    init.body = JSON.stringify(body);
  }
  const response = await fetch(`${base}${url}`, init);
  const type = response.headers.get('Content-Type') ?? '';
  const data = type.includes('json') ? await response.json() : Buffer.from(await response.arrayBuffer());
  return { status: response.status, data };
}

// Polls a build through the API until it is no longer queued or running.
async function apiBuildDone(base, id) {
  for (;;) {
    const { data } = await api(base, 'GET', `/api/builds/${id}`);
    if (!['queued', 'running'].includes(data.state)) return data;
    await new Promise((resolve) => setTimeout(resolve, 100));
  }
}

// ---- the page ----------------------------------------------------------------

async function shot(page, name) {
  if (!options.screenshots) return;
  // The view has drawn the scene it holds (two frames after the state the test waited for).
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: path.join(options.screenshots, `builder-${name}.png`) });
}

async function setValue(page, selector, value) {
  await page.waitForSelector(selector, { visible: true });
  await page.$eval(selector, (el, v) => {
    el.focus();
    el.value = v;
    el.dispatchEvent(new Event('input', { bubbles: true }));
    el.dispatchEvent(new Event('change', { bubbles: true }));
  }, String(value));
}

async function setChecked(page, selector, checked) {
  await page.waitForSelector(selector, { visible: true });
  await page.$eval(selector, (el, v) => { if (el.checked !== v) el.click(); }, checked);
}

// Waits for the page to finish a build other than `previous` (done or failed) and returns
// {id, state, text}.
async function pageBuild(page, previous) {
  await page.waitForFunction((prev) => {
    const s = document.getElementById('build-status');
    return s.dataset.build && s.dataset.build !== prev && ['done', 'failed', 'cancelled'].includes(s.dataset.state);
  }, {}, previous ?? '');
  return page.$eval('#build-status', (s) => ({ id: s.dataset.build, state: s.dataset.state, text: s.textContent }));
}

// Waits, in animation frames, for the 3D view to draw no frame for 60 of them in a row (at
// most 1200); returns {settled, frames (drawn so far), waited}.
async function viewSettles(page) {
  return page.evaluate(() => new Promise((resolve) => {
    const viewer = window.plantarchBuilder.viewer;
    let last = viewer.frames, still = 0, waited = 0;
    const tick = () => {
      waited++;
      if (viewer.frames === last) still++;
      else [last, still] = [viewer.frames, 0];
      if (still >= 60 || waited >= 1200) resolve({ settled: still >= 60, frames: viewer.frames, waited });
      else requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }));
}

async function shownNumber(page, id) {
  const text = await page.$eval(`#${id}`, (el) => el.firstChild.textContent);
  return Number(text.replace(/[^0-9.]/g, ''));
}

// ---- files -------------------------------------------------------------------

// Triangles of a GLB: every triangle-list primitive of every mesh a node uses.
function glbTriangles(bytes) {
  assert.equal(bytes.readUInt32LE(0), 0x46546c67, 'GLB magic');
  assert.equal(bytes.readUInt32LE(4), 2, 'GLB version');
  assert.equal(bytes.readUInt32LE(8), bytes.length, 'GLB length');
  const jsonLength = bytes.readUInt32LE(12);
  assert.equal(bytes.readUInt32LE(16), 0x4e4f534a, 'GLB JSON chunk');
  const doc = JSON.parse(bytes.subarray(20, 20 + jsonLength).toString('utf8'));
  let triangles = 0;
  for (const node of doc.nodes ?? []) {
    if (node.mesh === undefined) continue;
    for (const p of doc.meshes[node.mesh].primitives) triangles += doc.accessors[p.indices].count / 3;
  }
  return triangles;
}

// The JSON document of a GLB.
function glbDocument(bytes) {
  return JSON.parse(bytes.subarray(20, 20 + bytes.readUInt32LE(12)).toString('utf8'));
}

// Faces of an OBJ file, checking that every face's vertices exist.
function objFaces(text) {
  let vertices = 0, faces = 0;
  for (const line of text.split('\n')) {
    if (line.startsWith('v ')) vertices++;
    else if (line.startsWith('f ')) {
      faces++;
      for (const corner of line.slice(2).trim().split(/\s+/)) {
        const v = Number(corner.split('/')[0]);
        assert.ok(v >= 1 && v <= vertices, `face vertex ${v} of ${vertices}`);
      }
    }
  }
  return faces;
}

// ---- the scenario --------------------------------------------------------------

async function run() {
  const base = await startServer();
  step(`plantarch builder answers at ${base}`);
  browser = await puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    // Bounds for a hung server, not measures of speed: on a loaded machine a build or a
    // render can take minutes, and a wait in the page is one protocol call.
    protocolTimeout: 1800000,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1440,900'],
  });
  const page = await browser.newPage();
  page.setDefaultTimeout(1800000);
  await page.setViewport({ width: 1440, height: 900 });
  const pageErrors = [];
  page.on('pageerror', (e) => pageErrors.push(e.message));
  await page.goto(base);
  await page.waitForSelector('body[data-ready=true]');
  const first = await pageBuild(page, '');
  step(`the page loads and builds its first scene (${first.id}: ${first.state})`);

  // Block A: bean, a 3 x 3 grid, 40 days, built on request (the project named first, as the
  // file saved at the end, so the page's export and the command line's share every field).
  await setChecked(page, '#auto-build', false);
  await setValue(page, '#project-name', 'e2e_trial');
  await page.click('.block-card.open .species-button');
  await page.waitForSelector('.species-popup [data-species=bean]', { visible: true });
  // The thumbnails of the first species, drawn by the server's renderer, have arrived.
  await page.waitForFunction(() => [...document.querySelectorAll('.species-popup img')].slice(0, 7)
    .every((img) => img.complete && img.naturalWidth > 0));
  await shot(page, 'species-picker');
  await page.click('.species-popup [data-species=bean]');
  await page.select('.block-card.open select[name=layout]', 'grid');
  await setValue(page, '.block-card.open input[name=count-x]', 3);
  await setValue(page, '.block-card.open input[name=count-y]', 3);
  await setValue(page, '.block-card.open input[name=age]', 40);
  await page.click('#build');
  const built = await pageBuild(page, first.id);
  assert.equal(built.state, 'done', `the build of 3x3 bean: ${built.text}`);
  const status = (await api(base, 'GET', `/api/builds/${built.id}`)).data;
  const shownTriangles = await shownNumber(page, 'stat-triangles');
  assert.equal(shownTriangles, status.stats.triangles, 'triangles shown = the API\'s');
  assert.equal(await shownNumber(page, 'stat-plants'), 9, 'plants shown');
  assert.equal(status.stats.plants, 9, 'plants built');
  const viewTriangles = await page.evaluate(() => window.plantarchBuilder.viewer.triangles);
  assert.equal(viewTriangles, status.stats.triangles, 'triangles in the 3D view = the API\'s');
  step(`3x3 bean at 40 days: the page shows ${shownTriangles} triangles, as the API and the view`);

  // The view draws on demand: nothing while idle, frames while the camera is dragged, then
  // nothing again once its damping has settled.
  const idle = await viewSettles(page);
  assert.ok(idle.settled, `the idle view stops drawing (${idle.frames} frames after ${idle.waited} animation frames)`);
  const canvas = await page.evaluate(() => {
    const r = window.plantarchBuilder.viewer.renderer.domElement.getBoundingClientRect();
    return { x: r.x + r.width / 2, y: r.y + r.height / 2 };
  });
  await page.mouse.move(canvas.x, canvas.y);
  await page.mouse.down();
  await page.mouse.move(canvas.x + 120, canvas.y + 30, { steps: 8 });
  await page.mouse.up();
  const dragged = await viewSettles(page);
  assert.ok(dragged.frames > idle.frames, `dragging draws frames (${idle.frames} -> ${dragged.frames})`);
  assert.ok(dragged.settled, 'the view stops drawing once the camera has settled');
  step(`the view draws on demand: idle after ${idle.frames} frames, ${dragged.frames - idle.frames} frames for a drag`);
  await shot(page, 'scene');
  await page.select('#color-mode', 'organ');
  await page.waitForSelector('#legend .legend-row');
  await shot(page, 'organs');
  await page.select('#color-mode', 'natural');

  // A species parameter out of its range: the species reader's message, as the server gives it.
  const detail = (await api(base, 'GET', '/api/species/bean')).data;
  const [label, params] = Object.entries(detail.shoot_types)[0];
  const param = params.find((p) => p.path === 'internode_length_max');
  assert.ok(param, `bean's shoot type ${label} has internode_length_max`);
  const key = `shoot_types.${label}.internode_length_max`;
  await page.click('[data-tab=species]');
  await page.waitForSelector(`.param-row[data-key="${key}"]`);
  await setValue(page, 'input[name=species-filter]', 'internode_length_max');
  const random = param.kind.startsWith('random');
  if (random) await page.select(`select[name="sp-${key}-kind"]`, 'constant');
  await setValue(page, `input[name="sp-${key}${random ? '-0' : ''}"]`, '-5');
  await page.waitForSelector('#species-status[data-state=invalid]');
  const shownError = await page.$eval('#species-status', (el) => el.textContent);
  const checked = await api(base, 'POST', '/api/species/check', { base: 'bean', name: 'my_bean', changes: { [key]: '-5' } });
  assert.equal(checked.status, 400);
  assert.equal(shownError, checked.data.error, 'the species error shown = the server\'s');
  step(`an invalid species parameter shows: ${shownError}`);
  await shot(page, 'species-editor');

  // A block field out of its range: the build is refused with the project reader's line.
  await page.click('[data-tab=scene]');
  await setValue(page, '.block-card.open input[name=germination]', 2);
  await page.click('#build');
  await page.waitForSelector('#build-error:not([hidden])');
  const buildError = await page.$eval('#build-error', (el) => el.textContent);
  const refused = await api(base, 'POST', '/api/builds', { project: await page.evaluate(() => window.plantarchBuilder.projectFile()) });
  assert.equal(refused.status, 400);
  assert.ok(buildError.includes(refused.data.error), `the build error shown (${buildError}) holds the server's (${refused.data.error})`);
  step(`an invalid block field shows: ${refused.data.error}`);
  await setValue(page, '.block-card.open input[name=germination]', 1);
  await page.click('#build');
  const rebuilt = await pageBuild(page, built.id);
  assert.equal(rebuilt.state, 'done');

  // Growth: the slider grows the shown plants on; the result is the scene built at that age.
  await setValue(page, '#age-slider', 45);
  const grown = await pageBuild(page, rebuilt.id);
  assert.equal(grown.state, 'done', grown.text);
  const grownStatus = (await api(base, 'GET', `/api/builds/${grown.id}`)).data;
  assert.equal(grownStatus.from, rebuilt.id, 'the slider grows the shown build on');
  assert.deepEqual(grownStatus.ages, [45]);
  assert.equal(await shownNumber(page, 'stat-triangles'), grownStatus.stats.triangles);
  const project45 = await page.evaluate(() => window.plantarchBuilder.projectFile());
  const fresh = (await api(base, 'POST', '/api/builds', { project: project45 })).data;
  const freshStatus = await apiBuildDone(base, fresh.id);
  assert.deepEqual(freshStatus.stats, grownStatus.stats, 'grown from 40 to 45 days = built at 45 days');
  step(`the slider grows the scene to 45 days (${grown.id} from ${rebuilt.id}): ${grownStatus.stats.triangles} triangles, as built anew`);

  // Play: day by day, each day grown from the one before.
  await page.click('#play');
  await page.waitForFunction(() => window.plantarchBuilder.sceneAge() >= 47);
  await page.click('#play');
  await page.waitForFunction(() => !window.plantarchBuilder.playing);
  // The last day's build may still be on its way when play stops: the build shown catches up
  // with the scene's age within seconds (on a busy machine the status showed day 48 while
  // the scene was at 49).
  let played, playedStatus, age;
  for (let tries = 0; ; ++tries) {
    played = await page.$eval('#build-status', (s) => ({ id: s.dataset.build, state: s.dataset.state }));
    playedStatus = await apiBuildDone(base, played.id);
    age = await page.evaluate(() => window.plantarchBuilder.sceneAge());
    if (playedStatus.ages.length === 1 && playedStatus.ages[0] === age) break;
    assert.ok(tries < 50, `the shown build ${played.id} (ages ${playedStatus.ages}) never caught up with the scene's age ${age}`);
    await new Promise((resolve) => setTimeout(resolve, 200));
  }
  assert.ok(age >= 47, `played to ${age} days`);
  assert.deepEqual(playedStatus.ages, [age]);
  assert.ok(playedStatus.from, 'a played day is grown from the day before');
  if (played.state !== 'done') await pageBuild(page, '');
  step(`play grows the scene day by day to ${age} days`);
  await page.select('#color-mode', 'age');
  await page.waitForSelector('#legend .ramp');
  await shot(page, 'growth');
  await page.select('#color-mode', 'natural');

  // Export: the whole scene as GLB, one OBJ per plant, into folders under the output folder.
  const shownId = await page.$eval('#build-status', (s) => s.dataset.build);
  const shownStatus = (await api(base, 'GET', `/api/builds/${shownId}`)).data;
  await page.click('[data-tab=export]');
  await page.select('select[name=export-format]', 'glb');
  await setValue(page, 'input[name=export-folder]', 'e2e');
  await setValue(page, 'input[name=export-name]', 'scene');
  await page.click('#export-write');
  await page.waitForSelector('#export-result[data-state=done]');
  const glbPath = path.join(output, 'e2e', 'scene.glb');
  assert.ok(existsSync(glbPath), 'e2e/scene.glb written');
  const glb = readFileSync(glbPath);
  assert.equal(glbTriangles(glb), shownStatus.stats.triangles, 'the exported GLB holds the scene\'s triangles');
  const downloaded = await api(base, 'GET', `/api/export/download?build=${shownId}&format=glb&per_plant=false&name=scene`);
  assert.equal(downloaded.status, 200);
  assert.ok(downloaded.data.equals(glb), 'the download is the file written');
  step(`GLB export: e2e/scene.glb, ${glbTriangles(glb)} triangles, the same bytes as the download`);
  await page.select('select[name=export-format]', 'obj');
  await setChecked(page, 'input[name=per-plant]', true);
  await setValue(page, 'input[name=export-folder]', 'e2e/plants');
  await setValue(page, 'input[name=export-name]', 'plant');
  await page.$eval('#export-result', (el) => { el.dataset.state = ''; });
  await page.click('#export-write');
  await page.waitForSelector('#export-result[data-state=done]');
  const objs = readdirSync(path.join(output, 'e2e', 'plants')).filter((f) => f.endsWith('.obj'));
  assert.equal(objs.length, shownStatus.stats.plants, 'one OBJ per plant');
  for (const f of objs) assert.ok(objFaces(readFileSync(path.join(output, 'e2e', 'plants', f), 'utf8')) > 0, `${f} has faces`);
  step(`per-plant OBJ export: ${objs.length} files, each parses with faces`);
  await shot(page, 'export');

  // An export variant from the page: procedural textures (the view loads the textured scene)
  // and a node per organ; the GLB written holds a node per object of the scene, labelled in
  // its extras, the scene's triangles and its textures, and is the download of the same
  // variant. Then back to the defaults, for the byte-for-byte checks below.
  await setChecked(page, 'input[name=per-plant]', false);
  await page.select('select[name=export-format]', 'glb');
  await page.select('select[name=export-materials]', 'textured');
  await page.waitForSelector('#viewport[data-look="textured:512"]');
  await page.select('select[name=export-texture-size]', '256');
  await page.waitForSelector('#viewport[data-look="textured:256"]');
  // Bark and stems 256 texels a side; the leaves read their parts of one atlas (two 256-texel
  // squares with gutters, 272 wide) through KHR_texture_transform.
  const [viewMaps, viewParts] = await page.evaluate(() => {
    const maps = new Set();
    let parts = 0;
    window.plantarchBuilder.viewer.model.traverse((o) => {
      const m = o.userData.naturalMaterial;
      if (o.isMesh && m?.map?.image) maps.add(m.map.image.width);
      if (o.isMesh && m?.map?.image && m.map.repeat.y !== 1) parts++;
    });
    return [[...maps].sort(), parts];
  });
  assert.deepEqual(viewMaps, [256, 272], 'the view shows the textured materials, 256 texels a side');
  assert.ok(viewParts > 0, 'the view\'s leaves read their parts of the atlas');
  assert.equal(await page.$eval('#view-materials', (el) => el.value), 'textured');
  await page.select('select[name=export-nodes]', 'organ');
  await setValue(page, 'input[name=export-folder]', 'e2e/variant');
  await setValue(page, 'input[name=export-name]', 'organs');
  await page.$eval('#export-result', (el) => { el.dataset.state = ''; });
  await page.click('#export-write');
  await page.waitForSelector('#export-result[data-state=done]');
  const variantGlb = readFileSync(path.join(output, 'e2e', 'variant', 'organs.glb'));
  const variantDoc = glbDocument(variantGlb);
  const organNodes = variantDoc.nodes.filter((n) => n.extras?.organ && n.extras.objectID !== undefined);
  assert.equal(organNodes.length, shownStatus.stats.objects, 'a node per object, labelled');
  assert.ok(organNodes.some((n) => n.extras.organ === 'leaf' && /^leaf_s\d+_n\d+/.test(n.name)), 'leaf nodes named');
  assert.equal(glbTriangles(variantGlb), shownStatus.stats.triangles, 'the variant holds the scene\'s triangles');
  assert.ok(variantDoc.images.length > 0 &&
    variantDoc.materials.some((m) => m.pbrMetallicRoughness?.baseColorTexture), 'textured materials');
  const variantDownload = await api(base, 'GET',
    `/api/export/download?build=${shownId}&format=glb&name=organs&materials=textured&texture_size=256&nodes=organ`);
  assert.equal(variantDownload.status, 200);
  assert.ok(variantDownload.data.equals(variantGlb), 'the variant\'s download is the file written');
  assert.ok(variantDoc.extensionsRequired?.includes('KHR_texture_transform'), 'the leaves\' atlas');
  // Without the atlas (the checkbox, as --no-texture-atlas): an image per leaf colour.
  await setChecked(page, 'input[name=export-atlas]', false);
  await setValue(page, 'input[name=export-name]', 'own');
  await page.$eval('#export-result', (el) => { el.dataset.state = ''; });
  await page.click('#export-write');
  await page.waitForSelector('#export-result[data-state=done]');
  const ownDoc = glbDocument(readFileSync(path.join(output, 'e2e', 'variant', 'own.glb')));
  assert.ok(!ownDoc.extensionsUsed?.includes('KHR_texture_transform') &&
    ownDoc.images.length > variantDoc.images.length, 'no atlas: an image per leaf colour');
  await setChecked(page, 'input[name=export-atlas]', true);
  // GPU instances (--instancing gpu): organs of one shape drawn by one EXT_mesh_gpu_instancing node.
  await page.select('select[name=export-instancing]', 'gpu');
  await setValue(page, 'input[name=export-name]', 'gpu');
  await page.$eval('#export-result', (el) => { el.dataset.state = ''; });
  await page.click('#export-write');
  await page.waitForSelector('#export-result[data-state=done]');
  const gpuDoc = glbDocument(readFileSync(path.join(output, 'e2e', 'variant', 'gpu.glb')));
  assert.ok(gpuDoc.extensionsRequired?.includes('EXT_mesh_gpu_instancing') &&
    gpuDoc.nodes.some((n) => n.extensions?.EXT_mesh_gpu_instancing), 'GPU instances');
  await page.select('select[name=export-instancing]', 'shared');
  await page.evaluate(() => window.plantarchBuilder.viewer.frame());
  await shot(page, 'textured');
  // A refused variant shows the server's line in the page.
  await page.select('select[name=export-format]', 'ply');
  await page.$eval('#export-result', (el) => { el.dataset.state = ''; });
  await page.click('#export-download');
  await page.waitForSelector('#export-result[data-state=error]');
  const refusedVariant = await page.$eval('#export-result', (el) => el.textContent);
  assert.match(refusedVariant, /^materials = textured: textured materials are written in OBJ, glTF and USD only/);
  step(`textured GLB with a node per organ: ${organNodes.length} organ nodes, ${variantDoc.images.length} images; a PLY of it refused: ${refusedVariant}`);
  await page.select('select[name=export-format]', 'glb');
  await page.select('select[name=export-nodes]', 'kind');
  await page.select('select[name=export-materials]', 'flat');
  await page.waitForSelector('#viewport[data-look="flat"]');

  // The project saved from the page and run from the command line writes the bytes of the
  // page's export of the scene played day by day (an export of a grown scene writes the
  // project built anew); the same file uploaded into the page builds the same scene, whose
  // export is again the command line's file, byte for byte.
  await page.click('#project-save');
  await page.waitForSelector('body[data-saved=e2e_trial]');
  const saved = path.join(output, 'projects', 'e2e_trial.json');
  assert.ok(existsSync(saved), 'projects/e2e_trial.json written');
  const cliGlb = path.join(tmp, 'cli.glb');
  execFileSync(options.cli, ['project', 'run', saved, '-o', cliGlb], { stdio: 'pipe' });
  assert.ok(readFileSync(cliGlb).equals(glb), '`plantarch project run` writes the bytes of the played scene\'s export');
  const beforeUpload = await page.$eval('#build-status', (s) => s.dataset.build);
  const [chooser] = await Promise.all([page.waitForFileChooser(), page.click('#project-upload-button')]);
  await chooser.accept([saved]);
  const uploaded = await pageBuild(page, beforeUpload);
  assert.equal(uploaded.state, 'done');
  const uploadedStatus = (await api(base, 'GET', `/api/builds/${uploaded.id}`)).data;
  assert.equal(uploadedStatus.from, null, 'an uploaded project is built anew');
  assert.deepEqual(uploadedStatus.stats, shownStatus.stats, 'the uploaded project builds the scene grown day by day');
  await page.click('[data-tab=export]');
  await page.select('select[name=export-format]', 'glb');
  await setChecked(page, 'input[name=per-plant]', false);
  await setValue(page, 'input[name=export-folder]', 'e2e/uploaded');
  await setValue(page, 'input[name=export-name]', 'scene');
  await page.$eval('#export-result', (el) => { el.dataset.state = ''; });
  await page.click('#export-write');
  await page.waitForSelector('#export-result[data-state=done]');
  const pageGlb = readFileSync(path.join(output, 'e2e', 'uploaded', 'scene.glb'));
  assert.ok(readFileSync(cliGlb).equals(pageGlb), '`plantarch project run` writes the bytes of the page\'s export');
  step('the saved project, uploaded into the page and run by `plantarch project run`, gives the same GLB bytes');

  // Rendered preview from plantarch's renderer.
  await page.click('[data-tab=scene]');
  await page.click('#show-preview');
  await page.waitForSelector('.preview[data-state=done], .preview[data-state=error]');
  assert.equal(await page.$eval('.preview', (el) => el.dataset.state), 'done', 'the rendered preview loads');
  await shot(page, 'preview');

  // Cancel: a build the page asks for waits in the server's queue behind a large one (builds
  // run one at a time), and the Cancel button takes it out; the large one, still running
  // then (else the test proves nothing and fails), is cancelled through the API.
  const large = structuredClone(project45);
  large.blocks = [{ ...large.blocks[0], count: [30, 30], age: 40 }];
  delete large.blocks[0].seed;
  const blocker = (await api(base, 'POST', '/api/builds', { project: large })).data;
  assert.ok(blocker.id, `the large build is queued: ${JSON.stringify(blocker)}`);
  const beforeCancel = await page.$eval('#build-status', (s) => s.dataset.build);
  await page.click('#build');
  await page.waitForFunction((prev) => {
    const s = document.getElementById('build-status');
    return s.dataset.build && s.dataset.build !== prev && s.dataset.state === 'queued';
  }, {}, beforeCancel);
  await page.click('#cancel');
  const cancelled = await pageBuild(page, beforeCancel);
  assert.equal(cancelled.state, 'cancelled', `the page's build after Cancel: ${cancelled.text}`);
  assert.equal((await api(base, 'GET', `/api/builds/${cancelled.id}`)).data.state, 'cancelled');
  const blockerState = (await api(base, 'GET', `/api/builds/${blocker.id}`)).data.state;
  assert.ok(['queued', 'running'].includes(blockerState), `the large build was still under way (${blockerState})`);
  const stopped = await api(base, 'DELETE', `/api/builds/${blocker.id}`);
  assert.equal(stopped.data.state, 'cancelled', 'the large build, cancelled while it runs');
  assert.equal((await apiBuildDone(base, blocker.id)).state, 'cancelled');
  step(`Cancel takes the page's queued build ${cancelled.id} out; the running build ${blocker.id} stops through the API`);

  // The API refuses paths outside the output folder and state changes from other sites.
  for (const folder of ['../outside', '/tmp/plantarch-e2e-outside', 'e2e/../../outside']) {
    const r = await api(base, 'POST', '/api/export', { build: uploaded.id, format: 'glb', per_plant: false, folder, name: 'x' });
    assert.equal(r.status, 403, `export into '${folder}': ${JSON.stringify(r.data)}`);
  }
  assert.ok(!existsSync(path.join(tmp, 'outside')) && !existsSync('/tmp/plantarch-e2e-outside'), 'nothing written outside');
  const bad = await api(base, 'POST', '/api/projects/save', { name: '../escape', project: project45 });
  assert.ok([400, 403].includes(bad.status), `a project named '../escape': ${bad.status}`);
  assert.ok(!existsSync(path.join(tmp, 'escape.json')), 'no project written outside');
  const foreign = await api(base, 'POST', '/api/builds', { project: project45 }, { Origin: 'http://evil.example' });
  assert.equal(foreign.status, 403, 'a build requested by another site');
  step('the API refuses paths outside the output folder (403) and requests from other sites');

  await physiologySeason(page, base);
  await measuredSkeleton(page, base);
  await datasetScenario(page);
  assert.deepEqual(pageErrors, [], 'errors in the page');
}

// The colours of the 3D view's canvas: how many distinct ones (of a grid of samples), and
// whether more than the background shows.
async function canvasColors(page) {
  return page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => {
    const source = window.plantarchBuilder.viewer.renderer.domElement;
    const c = document.createElement('canvas');
    [c.width, c.height] = [source.width, source.height];
    const ctx = c.getContext('2d');
    ctx.drawImage(source, 0, 0);
    const data = ctx.getImageData(0, 0, c.width, c.height).data;
    const seen = new Set();
    for (let y = 0; y < c.height; y += 4)
      for (let x = 0; x < c.width; x += 4) {
        const i = 4 * (y * c.width + x);
        seen.add((data[i] >> 3) << 10 | (data[i + 1] >> 3) << 5 | data[i + 2] >> 3);
      }
    resolve(seen.size);
  })));
}

// A tiny project with a physiology season: the colour modes of light and carbon are offered
// only with their data (a disabled one says why), the season is built afresh from the page,
// its progress shown, and the scene coloured by absorbed PAR shows a ramp and many colours.
async function physiologySeason(page, base) {
  await page.click('#show-3d');
  const tooltip = (mode) => page.$eval(`#color-mode option[value=${mode}]`, (o) => ({ disabled: o.disabled, title: o.title }));
  const plain = await tooltip('light');
  assert.ok(plain.disabled && /physiology season/.test(plain.title), `light on a scene without a season: ${JSON.stringify(plain)}`);
  assert.ok((await tooltip('carbon')).disabled, 'carbon on a scene without a season');

  await page.click('[data-tab=scene]');
  await page.select('.block-card.open select[name=layout]', 'single');
  await setValue(page, '.block-card.open input[name=age]', 22);
  await page.click('[data-tab=environment]');
  await setChecked(page, 'input[name=physiology]', true);
  await setValue(page, 'input[name=days]', 2);
  await setValue(page, 'input[name=light-every]', 6);
  assert.equal(await page.$eval('#physiology-problems', (el) => el.hidden), true, 'the page sees nothing wrong');
  const project = await page.evaluate(() => window.plantarchBuilder.projectFile());
  assert.deepEqual(
    { ...project.physiology, location: undefined, start: undefined },
    { carbon: true, nitrogen: false, location: undefined, start: undefined, weather: null, clearness: 0.75, light_every: 6, days: 2, fertilise: [] },
  );
  // The progress lines the page shows while the season is built.
  await page.evaluate(() => {
    window.progressSeen = [];
    new MutationObserver(() => window.progressSeen.push(document.querySelector('.progress-text').textContent))
      .observe(document.querySelector('.progress-text'), { childList: true, characterData: true, subtree: true });
  });
  const before = await page.$eval('#build-status', (s) => s.dataset.build);
  await page.click('#build');
  const season = await pageBuild(page, before);
  assert.equal(season.state, 'done', `the season's build: ${season.text}`);
  const seasonStatus = (await api(base, 'GET', `/api/builds/${season.id}`)).data;
  assert.equal(seasonStatus.from, null, 'a season is built afresh');
  assert.equal(seasonStatus.stats.plants, 1);
  const progress = await page.evaluate(() => window.progressSeen.filter((t) => /Physiology/.test(t)));
  step(`a 2-day season of one bean (${season.id}) built afresh; progress lines seen: ${progress.slice(0, 3).join(' | ') || '(the season ran between two polls)'}`);
  // Growing the season on is refused by the server: the slider builds it again.
  await setValue(page, '#age-slider', 23);
  const again = await pageBuild(page, season.id);
  assert.equal(again.state, 'done', again.text);
  assert.equal((await api(base, 'GET', `/api/builds/${again.id}`)).data.from, null, 'the slider builds a season afresh');

  const glb = (await api(base, 'GET', `/api/builds/${again.id}/scene.glb`)).data;
  const jsonLength = glb.readUInt32LE(12);
  const doc = JSON.parse(glb.subarray(20, 20 + jsonLength).toString('utf8'));
  const columns = Object.keys(doc.extensions.EXT_structural_metadata.propertyTables[0].properties);
  for (const column of ['absorbed_par', 'carbohydrate_concentration'])
    assert.ok(columns.includes(column), `the season's scene has the ${column} column`);
  assert.equal((await tooltip('light')).disabled, false, 'light is offered for a scene with absorbed PAR');
  await page.evaluate(() => window.plantarchBuilder.viewer.frame());
  const naturalColors = await canvasColors(page);
  await page.select('#color-mode', 'light');
  await page.waitForSelector('#legend .ramp');
  const legend = await page.evaluate(() => ({
    title: document.getElementById('legend-title').textContent,
    min: Number(document.getElementById('legend-min').dataset.value),
    max: Number(document.getElementById('legend-max').dataset.value),
    rows: [...document.querySelectorAll('#legend .legend-row')].map((r) => r.textContent),
  }));
  assert.match(legend.title, /absorbed PAR.*µmol m⁻² s⁻¹/);
  assert.ok(legend.min >= 0 && legend.max > legend.min, `the legend's range: ${legend.min} to ${legend.max}`);
  // Objects without the data (stems and petioles of a season's plants) are listed once, grey.
  assert.ok(legend.rows.every((r) => r === 'no data'), `legend rows: ${legend.rows}`);
  const lightColors = await canvasColors(page);
  assert.ok(lightColors > 20, `the canvas coloured by light shows ${lightColors} colours (natural: ${naturalColors})`);
  await shot(page, 'physiology-light');
  assert.equal((await tooltip('carbon')).disabled, false, 'carbon is offered after a season with the budget');
  await page.select('#color-mode', 'carbon');
  await page.waitForFunction(() => /carbohydrate/.test(document.getElementById('legend-title')?.textContent));
  const carbonColors = await canvasColors(page);
  assert.ok(carbonColors > 5, `the canvas coloured by carbon shows ${carbonColors} colours`);
  await shot(page, 'physiology-carbon');
  await page.select('#color-mode', 'natural');
  step(`colour by light: a ramp of ${legend.min.toFixed(1)} to ${legend.max.toFixed(1)} µmol m⁻² s⁻¹, ${lightColors} colours on the canvas`);
}

// A measured skeleton: the repository's digitised pepper, copied under the output folder,
// named relative to OUTPUT/projects/ as the page's other files are. A bad skeleton file is
// refused with the server's one line; the good one builds one plant, labelled with its block;
// "Bend under load" with a softer wood bends a grown plant beside it (other GLB bytes).
async function measuredSkeleton(page, base) {
  const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
  mkdirSync(path.join(output, 'skeletons'), { recursive: true });
  copyFileSync(path.join(root, 'examples/skeletons/pepper_digitised.csv'), path.join(output, 'skeletons/pepper.csv'));
  writeFileSync(path.join(output, 'skeletons/bad.csv'), 'id,parent,x,y,z\n0,,0,0,0\n1,0,nan,0,1\n');
  await page.click('[data-tab=environment]');
  await setChecked(page, 'input[name=physiology]', false);
  await page.click('[data-tab=scene]');
  await page.click('.block-card.open .species-button');
  await page.click('.species-popup [data-species=capsicum]');
  await page.select('.block-card.open select[name=layout]', 'skeleton');
  await setValue(page, '.block-card.open input[name=skeleton-file]', '../skeletons/bad.csv');
  await page.select('.block-card.open select[name=skeleton-unit]', '0.01');
  await setValue(page, '.block-card.open input[name=age]', 60);
  await page.click('#build');
  await page.waitForSelector('#build-error:not([hidden])');
  const badError = await page.$eval('#build-error', (el) => el.textContent);
  assert.match(badError, /bad\.csv:3/, `a bad skeleton's error: ${badError}`);
  step(`a bad skeleton file shows: ${badError}`);

  await setValue(page, '.block-card.open input[name=skeleton-file]', '../skeletons/pepper.csv');
  const before = await page.$eval('#build-status', (s) => s.dataset.build);
  await page.click('#build');
  const straight = await pageBuild(page, before);
  assert.equal(straight.state, 'done', `the skeleton's build: ${straight.text}`);
  const status = (await api(base, 'GET', `/api/builds/${straight.id}`)).data;
  assert.equal(status.stats.plants, 1, 'one measured plant');
  assert.equal(await shownNumber(page, 'stat-plants'), 1, 'plants shown');
  await shot(page, 'skeleton');

  // A grown capsicum beside it, built straight, then with "Bend under load" and a softer wood:
  // its shoots bend (other GLB bytes, a lower plant); the measured one is held as measured.
  await page.click('#add-block');
  await page.select('.block-card.open select[name=layout]', 'single');
  await setValue(page, '.block-card.open input[name=age]', 60);
  await page.click('#build');
  const upright = await pageBuild(page, straight.id);
  assert.equal(upright.state, 'done', `the grown capsicum's build: ${upright.text}`);
  await setChecked(page, '.block-card.open input[name=bend]', true);
  await setValue(page, '.block-card.open input[name=elastic-modulus]', 1e9);
  const file = await page.evaluate(() => window.plantarchBuilder.projectFile());
  assert.deepEqual(
    file.blocks.map((b) => [b.layout, b.skeleton?.file, b.skeleton?.unit, b.bend, b.elastic_modulus]),
    [['skeleton', '../skeletons/pepper.csv', 0.01, false, null], ['single', undefined, undefined, true, 1e9]],
  );
  await page.click('#build');
  const bent = await pageBuild(page, upright.id);
  assert.equal(bent.state, 'done', `the bent capsicum's build: ${bent.text}`);
  const [a, b] = await Promise.all([upright.id, bent.id].map(async (id) => (await api(base, 'GET', `/api/builds/${id}/scene.glb`)).data));
  assert.ok(!a.equals(b), 'bending changes the scene');
  const heights = await Promise.all([upright.id, bent.id].map(async (id) => (await api(base, 'GET', `/api/builds/${id}`)).data.stats.height));
  assert.ok(heights[1] < heights[0], `bent lower: ${heights}`);
  await page.evaluate(() => window.plantarchBuilder.viewer.frame());
  await shot(page, 'bending');
  step(`a measured pepper skeleton built (${straight.id}); a capsicum bent under load (${bent.id}): ${heights[0].toFixed(3)} m upright, ${heights[1].toFixed(3)} m bent`);
}

// The Dataset tab: examples/datasets/tiny.json, copied into the output folder's datasets/, is
// opened and checked; an error shows the spec reader's line and field; sample 0 is previewed
// (its five pictures load at the spec's size) and a run of 2 samples writes the dataset.
async function datasetScenario(page) {
  const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
  mkdirSync(path.join(output, 'datasets'), { recursive: true });
  copyFileSync(path.join(root, 'examples/datasets/tiny.json'), path.join(output, 'datasets/tiny.json'));
  await page.click('.tab[data-tab=dataset]');
  await page.waitForFunction(() =>
    [...document.querySelectorAll('#dataset-file option')].some((o) => o.value === 'datasets/tiny.json'));
  await page.select('#dataset-file', 'datasets/tiny.json');
  await page.click('#dataset-open');
  await page.waitForSelector('#dataset-check[data-state=valid]');
  const tiny = await page.$eval('#dataset-spec', (el) => el.value);
  await setValue(page, '#dataset-spec', tiny.replace('"age": [12, 18]', '"age": [12, -18]'));
  await page.click('#dataset-check-button');
  await page.waitForSelector('#dataset-check[data-state=error]');
  const shown = await page.$eval('#dataset-check', (el) => el.textContent);
  assert.match(shown, /scene\/species\/0\/age/, `the spec's error: ${shown}`);
  step(`a bad dataset spec shows: ${shown}`);
  await setValue(page, '#dataset-spec', tiny);
  await page.select('select[name=dataset-count]', '1');
  await page.click('#dataset-preview');
  await page.waitForSelector('#dataset-previews[data-state=done]');
  const pictures = await page.waitForFunction(() => {
    const images = [...document.querySelectorAll('#dataset-previews img')];
    return images.length === 5 && images.every((i) => i.complete) &&
      images.map((i) => [i.dataset.picture, i.naturalWidth, i.naturalHeight]);
  });
  const sizes = await pictures.jsonValue();
  for (const [name, w, h] of sizes) assert.deepEqual([w, h], [160, 120], `the preview's ${name} picture`);
  await setValue(page, 'input[name=dataset-samples]', 2);
  await page.click('#dataset-run');
  await page.waitForFunction(() =>
    ['done', 'failed', 'cancelled'].includes(document.getElementById('dataset-run-status').dataset.state));
  const run = await page.$eval('#dataset-run-status', (el) => ({ state: el.dataset.state, text: el.textContent }));
  assert.equal(run.state, 'done', `the dataset run: ${run.text}`);
  for (const file of ['dataset.json', 'manifest-0-of-1.json', 'samples/000001/rgb.png'])
    assert.ok(existsSync(path.join(output, 'datasets/tiny', file)), `the run wrote ${file}`);
  assert.ok(!existsSync(path.join(output, 'datasets/tiny/samples/000002')), 'two samples');
  await page.$eval('#dataset-spec', (el) => { el.scrollTop = 0; });
  await shot(page, 'dataset');
  step(`tiny.json: sample 0 previewed (${sizes.map((s) => s[0]).join(', ')}); a run of 2 samples: ${run.text}`);
}

let failed = false;
try {
  await run();
  console.log('builder_e2e: every step passed');
} catch (e) {
  failed = true;
  console.error(`builder_e2e: FAILED: ${e.message}`);
  if (serverLog) console.error(`plantarch builder said:\n${serverLog.slice(-4000)}`);
} finally {
  await browser?.close();
  if (server && server.exitCode === null) {
    server.kill('SIGTERM');
    await new Promise((resolve) => server.once('exit', resolve));
  }
  rmSync(tmp, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
