// Picks one organ of a GLB written with `--nodes organ` as a viewer's user would: three.js
// (GLTFLoader, in Debian's headless Chromium driven by puppeteer-core) loads the file, a ray
// from the camera through the organ's centre on the screen picks it (the first mesh the ray
// hits must belong to that organ's node: seen, not hidden behind leaves), and the picked node
// is highlighted (an emissive glow and an outline shell) with its labels shown beside it.
// Prints one JSON line: the picked node's name and extras, the triangles three.js holds, the
// organ nodes by kind. With --png, also saves the picture.
//
//   node pick_organ.mjs FILE.glb [--organ fruit] [--png OUT.png] [--size 900x1100]
//
// Exits 1 when no organ of that kind can be picked. CHROMIUM overrides /usr/bin/chromium.
import http from 'node:http';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const options = { file: null, organ: 'fruit', png: null, width: 900, height: 1100 };
for (let i = 2; i < process.argv.length; i++) {
  const a = process.argv[i];
  if (a === '--organ') options.organ = process.argv[++i];
  else if (a === '--png') options.png = path.resolve(process.argv[++i]);
  else if (a === '--size') [options.width, options.height] = process.argv[++i].split('x').map(Number);
  else if (!options.file && !a.startsWith('--')) options.file = a;
  else throw new Error(`pick_organ: unknown argument '${a}' (valid: FILE.glb --organ KIND --png OUT --size WxH)`);
}
if (!options.file) throw new Error('pick_organ: give a GLB written with --nodes organ');

const page = `<!doctype html><html><head><style>
html, body { margin: 0; background: #eef2f5; font: 15px/1.35 "DejaVu Sans", sans-serif; }
#label { position: absolute; padding: 8px 11px; background: rgba(255,255,255,.93);
         border: 2px solid #e8590c; border-radius: 6px; color: #222; white-space: pre; }
#label b { color: #c2410c; }
#title { position: absolute; left: 14px; top: 10px; color: #333; }
</style></head><body><div id="title"></div><div id="label" hidden></div>
<script type="importmap">
{"imports": {"three": "/node_modules/three/build/three.module.js",
             "three/addons/": "/node_modules/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const count = (g) => (g.index ? g.index.count : g.attributes.position.count) / 3;

window.pick = async (url, organ, width, height) => {
  const gltf = await new GLTFLoader().loadAsync(url);
  const root = gltf.scene;
  root.updateMatrixWorld(true);
  let triangles = 0;
  const kinds = {};
  root.traverse((o) => {
    if (o.isMesh) triangles += count(o.geometry);
    // GLTFLoader puts a node's extras in its object's userData.
    if (o.userData?.organ && o.userData.objectID !== undefined)
      kinds[o.userData.organ] = (kinds[o.userData.organ] ?? 0) + 1;
  });
  const candidates = [];
  root.traverse((o) => { if (o.userData?.organ === organ && o.userData.objectID !== undefined) candidates.push(o); });

  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(width, height);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  document.body.prepend(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xeef2f5);
  scene.add(new THREE.HemisphereLight(0xf4f8ff, 0x8a7f6a, 2.0));
  const sun = new THREE.DirectionalLight(0xffffff, 2.2);
  sun.position.set(3, 6, 4);
  scene.add(sun);
  scene.add(root);
  const ground = new THREE.Mesh(new THREE.CircleGeometry(1, 64),
                                new THREE.MeshStandardMaterial({ color: 0xd8d2c4, roughness: 1 }));
  ground.rotation.x = -Math.PI / 2;
  scene.add(ground);

  // The camera frames the plant from the side each candidate faces (its offset from the
  // plant's axis), a little above; the first candidate a ray from there reaches is picked.
  const box = new THREE.Box3().setFromObject(root);
  const size = box.getSize(new THREE.Vector3()), center = box.getCenter(new THREE.Vector3());
  ground.scale.setScalar(Math.max(size.x, size.z) * 0.45);
  const camera = new THREE.PerspectiveCamera(30, width / height, 0.01, 100);
  const radius = size.length() / 2;
  const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 0.92;
  const ray = new THREE.Raycaster();
  const meshOf = (o) => { let m = null; o.traverse((c) => { if (!m && c.isMesh) m = c; }); return m; };
  const within = (hit, node) => { for (let o = hit; o; o = o.parent) if (o === node) return true; return false; };
  let picked = null, tried = 0;
  for (const node of candidates) {
    tried++;
    const at = new THREE.Box3().setFromObject(node).getCenter(new THREE.Vector3());
    const side = new THREE.Vector3(at.x - center.x, 0, at.z - center.z);
    if (side.lengthSq() < 1e-8) side.set(1, 0, 1);
    side.normalize();
    const direction = side.add(new THREE.Vector3(0, 0.35, 0)).normalize();
    camera.position.copy(center).addScaledVector(direction, distance);
    camera.lookAt(center);
    camera.updateMatrixWorld(true);
    const ndc = at.clone().project(camera);
    ray.setFromCamera(new THREE.Vector2(ndc.x, ndc.y), camera);
    const hits = ray.intersectObject(root, true);
    if (hits.length && within(hits[0].object, node)) {
      picked = { node, ndc, hit: hits[0].object };
      break;
    }
  }
  if (!picked) return { triangles, kinds, candidates: candidates.length, picked: null };

  // The highlight: the picked organ glows orange, with a back-face shell as its outline.
  const node = picked.node;
  const meshes = [];
  node.traverse((o) => { if (o.isMesh) meshes.push(o); });
  meshes.forEach((o) => {
    o.material = o.material.clone();
    o.material.emissive = new THREE.Color(0xff5a00);
    o.material.emissiveIntensity = 0.85;
    const shell = new THREE.Mesh(o.geometry, new THREE.MeshBasicMaterial({ color: 0xff2200, side: THREE.BackSide }));
    const c = new THREE.Box3().setFromBufferAttribute(o.geometry.attributes.position).getCenter(new THREE.Vector3());
    shell.position.copy(c).multiplyScalar(-0.12);
    shell.scale.setScalar(1.12);
    o.add(shell);
  });
  renderer.render(scene, camera);

  // Its labels beside it, with a line to it.
  const e = node.userData;
  const label = document.getElementById('label');
  label.innerHTML = '<b>' + node.name + '</b>\\n' +
    Object.entries(e).filter(([k]) => k !== 'name').map(([k, v]) => k + ': ' + (typeof v === 'number' && !Number.isInteger(v) ? v.toFixed(1) : v)).join('\\n');
  label.hidden = false;
  const px = (picked.ndc.x + 1) / 2 * width, py = (1 - picked.ndc.y) / 2 * height;
  // In the margin on the organ's side of the picture, below it.
  const left = px > width / 2 ? width - label.offsetWidth - 16 : 16;
  label.style.left = left + 'px';
  label.style.top = Math.max(40, Math.min(height - label.offsetHeight - 16, py + 40)) + 'px';
  const svg = document.createElementNS('http://www.w3.org/2000/svg', 'svg');
  svg.setAttribute('width', width); svg.setAttribute('height', height);
  svg.style.position = 'absolute'; svg.style.left = '0'; svg.style.top = '0';
  const lx = parseFloat(label.style.left) + (left < px ? label.offsetWidth : 0);
  const ly = parseFloat(label.style.top) + label.offsetHeight / 2;
  svg.innerHTML = '<line x1="' + px + '" y1="' + py + '" x2="' + lx + '" y2="' + ly +
    '" stroke="#e8590c" stroke-width="2.5"/><circle cx="' + px + '" cy="' + py + '" r="5" fill="none" stroke="#e8590c" stroke-width="2"/>';
  document.body.append(svg);
  document.getElementById('title').textContent =
    'three.js: ' + organ + ' picked by a ray from the camera (' + triangles + ' triangles, ' +
    Object.values(kinds).reduce((a, b) => a + b, 0) + ' organ nodes)';
  return { triangles, kinds, candidates: candidates.length, tried,
           picked: { name: node.name, extras: e, hitMesh: picked.hit.name } };
};
window.ready = true;
</script></body></html>`;

const server = http.createServer(async (req, res) => {
  try {
    if (req.url === '/') {
      res.writeHead(200, { 'content-type': 'text/html' });
      return res.end(page);
    }
    if (req.url === '/file.glb') {
      res.writeHead(200, { 'content-type': 'model/gltf-binary' });
      return res.end(await readFile(options.file));
    }
    if (req.url.startsWith('/node_modules/')) {
      const bytes = await readFile(path.join(here, decodeURIComponent(req.url)));
      res.writeHead(200, { 'content-type': 'text/javascript' });
      return res.end(bytes);
    }
    res.writeHead(404);
    res.end();
  } catch (e) {
    res.writeHead(500);
    res.end(String(e));
  }
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  protocolTimeout: 600000,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
let status = 0;
try {
  const tab = await browser.newPage();
  await tab.setViewport({ width: options.width, height: options.height });
  await tab.goto(`http://127.0.0.1:${server.address().port}/`);
  await tab.waitForFunction('window.ready === true');
  const result = await tab.evaluate((o) => window.pick('/file.glb', o.organ, o.width, o.height),
                                    { organ: options.organ, width: options.width, height: options.height });
  console.log(JSON.stringify({ file: options.file, ...result }));
  if (!result.picked) status = 1;
  else if (options.png) await tab.screenshot({ path: options.png });
} finally {
  await browser.close();
  server.close();
}
process.exit(status);
