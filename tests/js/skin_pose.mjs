// A skinned plant (plantarch --skin) drawn by three.js in headless Chromium in two poses side
// by side: as built (the bind pose) and swayed by wind, every joint turned about the same
// horizontal axis by an angle growing toward the tips, as a wind shader would drive it. Prints
// how far the highest vertex moved; writes the picture when given a PNG path.
// Usage: node skin_pose.mjs FILE.glb [OUT.png] [ANGLE_DEGREES]  (CHROMIUM overrides /usr/bin/chromium)
import http from 'node:http';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const [file, out, angleText] = process.argv.slice(2);
if (!file) {
  console.error('usage: node skin_pose.mjs FILE.glb [OUT.png] [ANGLE_DEGREES]');
  process.exit(2);
}
const angle = Number(angleText || 1.5);
const page = `<!doctype html><body style="margin:0;background:#fff">
<script type="importmap">
{"imports": {"three": "/node_modules/three/build/three.module.js",
             "three/addons/": "/node_modules/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const W = 1200, H = 800;
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setSize(W, H);
renderer.setScissorTest(true);
document.body.appendChild(renderer.domElement);
// The highest point of the skinned meshes, as three.js places their vertices.
function top(scene) {
  scene.updateMatrixWorld(true);
  const v = new THREE.Vector3(), best = new THREE.Vector3(0, -Infinity, 0);
  scene.traverse((o) => {
    if (!o.isSkinnedMesh) return;
    for (let i = 0; i < o.geometry.attributes.position.count; i++) {
      o.getVertexPosition(i, v).applyMatrix4(o.matrixWorld);
      if (v.y > best.y) best.copy(v);
    }
  });
  return best;
}
window.draw = (url, degrees) => new Promise((resolve, reject) => {
  new GLTFLoader().load(url, (gltf) => {
    const scenes = [gltf.scene];
    // A plain clone's skinned meshes would keep the first copy's bones: load it again.
    new GLTFLoader().load(url, (second) => {
      scenes.push(second.scene);
      const before = top(scenes[0]);
      // Sway: each bone turned about world x (wind along -z of the view), by an angle
      // proportional to its depth in the skeleton.
      const bones = [];
      scenes[1].traverse((o) => { if (o.isBone) bones.push(o); });
      const depth = (b) => { let d = 0; while (b.parent && b.parent.isBone) { d++; b = b.parent; } return d; };
      const deepest = Math.max(1, ...bones.map(depth));
      scenes[1].updateMatrixWorld(true);
      for (const b of bones) {
        const a = THREE.MathUtils.degToRad(degrees) * (0.3 + depth(b) / deepest);
        const worldAxis = new THREE.Vector3(1, 0, 0);
        const parentTurn = new THREE.Quaternion();
        b.parent.getWorldQuaternion(parentTurn);
        const local = worldAxis.applyQuaternion(parentTurn.invert());
        b.quaternion.premultiply(new THREE.Quaternion().setFromAxisAngle(local, a));
      }
      const after = top(scenes[1]);
      const box = new THREE.Box3().setFromObject(scenes[0]);
      const size = box.getSize(new THREE.Vector3()), centre = box.getCenter(new THREE.Vector3());
      const camera = new THREE.PerspectiveCamera(30, (W / 2) / H, 0.01, 100);
      const distance = 1.5 * Math.max(size.y, size.x, size.z) / (2 * Math.tan(THREE.MathUtils.degToRad(15)));
      camera.position.set(centre.x + distance, centre.y + 0.15 * size.y, centre.z);
      camera.lookAt(centre);
      scenes.forEach((scene, i) => {
        scene.add(new THREE.HemisphereLight(0xffffff, 0x445533, 2.2));
        const sun = new THREE.DirectionalLight(0xffffff, 1.8);
        sun.position.set(1, 3, 2);
        scene.add(sun);
        renderer.setViewport(i * W / 2, 0, W / 2, H);
        renderer.setScissor(i * W / 2, 0, W / 2, H);
        renderer.setClearColor(i ? 0xeef3fa : 0xf7f7f2, 1);
        renderer.clear();
        renderer.render(scene, camera);
      });
      resolve({ bones: bones.length, deepest, top: before.toArray(), swayedTop: after.toArray(),
                moved: before.distanceTo(after) });
    }, undefined, (e) => reject(String(e)));
  }, undefined, (e) => reject(String(e)));
});
window.ready = true;
</script>`;

const server = http.createServer(async (req, res) => {
  try {
    if (req.url === '/') {
      res.writeHead(200, { 'content-type': 'text/html' });
      return res.end(page);
    }
    if (req.url === '/file') {
      res.writeHead(200, { 'content-type': 'application/octet-stream' });
      return res.end(await readFile(file));
    }
    if (req.url.startsWith('/node_modules/')) {
      res.writeHead(200, { 'content-type': 'text/javascript' });
      return res.end(await readFile(path.join(here, decodeURIComponent(req.url))));
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
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1200,800'],
});
let status = 0;
try {
  const tab = await browser.newPage();
  await tab.setViewport({ width: 1200, height: 800 });
  await tab.goto(`http://127.0.0.1:${server.address().port}/`);
  await tab.waitForFunction('window.ready === true');
  const result = await tab.evaluate((d) => window.draw('/file', d), angle);
  console.log(JSON.stringify({ file, ...result }));
  if (out) {
    const canvas = await tab.$('canvas');
    await canvas.screenshot({ path: out });
  }
} catch (e) {
  console.log(JSON.stringify({ file, error: String(e) }));
  status = 1;
} finally {
  await browser.close();
  server.close();
}
process.exit(status);
