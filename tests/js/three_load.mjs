// Loads glTF files with three.js's GLTFLoader in headless Chromium (Debian's, driven by
// puppeteer-core) and prints one JSON line per file: triangles, meshes, the triangles drawn
// (an InstancedMesh of EXT_mesh_gpu_instancing once per instance) and InstancedMeshes, the vertex
// attributes three.js sees (the labels _PLANT_ID, _OBJECT_ID, _ORGAN among them) and, for an
// animated file, the triangles shown at each key time of its first animation played by an
// AnimationMixer.
// Usage: node three_load.mjs FILE...   (CHROMIUM overrides /usr/bin/chromium)
import http from 'node:http';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const here = path.dirname(fileURLToPath(import.meta.url));
const files = process.argv.slice(2);
const page = `<!doctype html><script type="importmap">
{"imports": {"three": "/node_modules/three/build/three.module.js",
             "three/addons/": "/node_modules/three/examples/jsm/"}}</script>
<script type="module">
import { AnimationMixer } from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
const count = (g) => (g.index ? g.index.count : g.attributes.position.count) / 3;
// Triangles of the meshes a viewer draws: visible, with a world scale that is not zero.
function shownTriangles(scene) {
  scene.updateMatrixWorld(true);
  let n = 0;
  scene.traverseVisible((o) => {
    if (o.isMesh && Math.abs(o.matrixWorld.determinant()) > 0) n += count(o.geometry);
  });
  return n;
}
// Triangles and distinct _OBJECT_ID labels of the meshes under a node.
function tally(root) {
  let triangles = 0; const objects = new Set();
  root.traverse((o) => {
    if (!o.isMesh) return;
    triangles += count(o.geometry);
    const ids = o.geometry.attributes._object_id;
    if (ids) for (let i = 0; i < ids.count; i++) objects.add(ids.getX(i));
  });
  return { triangles, objects };
}
window.loadFile = (url) => new Promise((resolve, reject) => {
  new GLTFLoader().setMeshoptDecoder(MeshoptDecoder).load(url, async (gltf) => {
    let triangles = 0, meshes = 0, drawn = 0, instanced = 0, mislabelled = 0;
    const attributes = new Set();
    gltf.scene.traverse((o) => {
      if (!o.isMesh) return;
      meshes++;
      triangles += count(o.geometry);
      // EXT_mesh_gpu_instancing: an InstancedMesh draws its triangles once per instance.
      drawn += count(o.geometry) * (o.isInstancedMesh ? o.count : 1);
      if (o.isInstancedMesh) {
        // Its per-instance labels: instance i's _OBJECT_ID is the i-th of the node's objectIDs
        // (extras), and its name the i-th of its instances.
        instanced++;
        const ids = o.geometry.attributes._OBJECT_ID, u = o.userData;
        if (!ids || ids.count !== o.count || (u.instances ?? []).length !== o.count ||
            (u.objectIDs ?? []).some((id, i) => ids.getX(i) !== id)) mislabelled++;
      }
      Object.keys(o.geometry.attributes).forEach((a) => attributes.add(a));
    });
    const result = { triangles, meshes, attributes: [...attributes].sort(),
                     objects: tally(gltf.scene).objects.size, drawn, instanced, mislabelled };
    // MSFT_lod (which GLTFLoader leaves out of the scene): each level's nodes loaded by
    // index, with their triangles and objects, and how many of those are the full level's.
    const json = gltf.parser.json;
    const lods = (json.nodes || []).filter((n) => n.extensions && n.extensions.MSFT_lod);
    if (lods.length) {
      const full = tally(gltf.scene).objects;
      result.levels = [];
      for (let k = 0; k < lods[0].extensions.MSFT_lod.ids.length; k++) {
        let t = 0; const objects = new Set();
        for (const n of lods) {
          const node = await gltf.parser.getDependency('node', n.extensions.MSFT_lod.ids[k]);
          const one = tally(node);
          t += one.triangles;
          one.objects.forEach((o) => objects.add(o));
        }
        result.levels.push({ triangles: t, objects: objects.size,
                             shared: [...objects].filter((o) => full.has(o)).length });
      }
    }
    // Textured materials (--materials textured): those with a decoded base colour map, and
    // how many of them also have a normal map, a roughness map and an alpha test (MASK).
    const materials = new Map();
    gltf.scene.traverse((o) => {
      if (o.isMesh && o.material.map && o.material.map.image) materials.set(o.material.uuid, o.material);
    });
    if (materials.size) {
      const all = [...materials.values()];
      result.textured = { materials: all.length,
                          normal: all.filter((m) => m.normalMap).length,
                          roughness: all.filter((m) => m.roughnessMap).length,
                          alphaTest: all.filter((m) => m.alphaTest > 0).length,
                          width: Math.max(...all.map((m) => m.map.image.width)),
                          // Atlas parts (KHR_texture_transform): materials whose base colour
                          // map is offset or scaled, and whether every map of each material
                          // reads the same part (offset and repeat) as its base colour.
                          transformed: all.filter((m) => m.map.offset.x !== 0 || m.map.offset.y !== 0 ||
                                                         m.map.repeat.x !== 1 || m.map.repeat.y !== 1).length,
                          sameParts: all.every((m) => [m.normalMap, m.roughnessMap, m.aoMap].every((t) =>
                            !t || (t.offset.equals(m.map.offset) && t.repeat.equals(m.map.repeat)))),
                          parts: all.map((m) => [m.map.offset.x, m.map.offset.y, m.map.repeat.x, m.map.repeat.y]
                            .map((x) => Math.round(x * 1e4) / 1e4)).sort() };
    }
    // Skinned meshes (--skin): how many, the bones they move and the file's joints; and for
    // every file, the world box of its vertices as three.js places them (bones applied), to
    // compare a skinned plant at its bind pose with the same plant unskinned.
    const skinned = [];
    gltf.scene.traverse((o) => { if (o.isSkinnedMesh) skinned.push(o); });
    if (skinned.length) {
      const bones = new Set(skinned.flatMap((m) => m.skeleton.bones.map((b) => b.uuid)));
      result.skinned = { meshes: skinned.length, bones: bones.size,
                         joints: (gltf.parser.json.skins || []).reduce((n, s) => n + s.joints.length, 0) };
    }
    gltf.scene.updateMatrixWorld(true);
    const v = gltf.scene.position.clone();  // a Vector3
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    gltf.scene.traverse((o) => {
      if (!o.isMesh) return;
      for (let i = 0; i < o.geometry.attributes.position.count; i++) {
        o.getVertexPosition(i, v);
        v.applyMatrix4(o.matrixWorld);
        [v.x, v.y, v.z].forEach((x, k) => { lo[k] = Math.min(lo[k], x); hi[k] = Math.max(hi[k], x); });
      }
    });
    result.box = [...lo, ...hi];
    // An animation played as a viewer plays it: the triangles shown at each key time.
    if (gltf.animations.length) {
      const clip = gltf.animations[0];
      const times = [...new Set(clip.tracks.flatMap((t) => [...t.times]))].sort((a, b) => a - b);
      const mixer = new AnimationMixer(gltf.scene);
      mixer.clipAction(clip).play();
      result.animation = clip.name;
      result.tracks = clip.tracks.length;
      // The last key ends the clip (where a looping player starts over): not a frame.
      result.frames = times.slice(0, -1).map((t) => {
        mixer.setTime(t);
        return shownTriangles(gltf.scene);
      });
    }
    resolve(result);
  }, undefined, (e) => reject(String(e)));
});
window.ready = true;
</script>`;

// Serves the page, three.js from node_modules, and the files under /file/<index>.
const server = http.createServer(async (req, res) => {
  try {
    if (req.url === '/') {
      res.writeHead(200, { 'content-type': 'text/html' });
      return res.end(page);
    }
    if (req.url.startsWith('/file/')) {
      const bytes = await readFile(files[Number(req.url.slice(6))]);
      res.writeHead(200, { 'content-type': 'application/octet-stream' });
      return res.end(bytes);
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
const { port } = server.address();
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-gpu'],
});
let failed = false;
try {
  const tab = await browser.newPage();
  await tab.goto(`http://127.0.0.1:${port}/`);
  await tab.waitForFunction('window.ready === true');
  for (let i = 0; i < files.length; i++) {
    try {
      const result = await tab.evaluate((u) => window.loadFile(u), `/file/${i}`);
      console.log(JSON.stringify({ file: files[i], ...result }));
    } catch (e) {
      failed = true;
      console.log(JSON.stringify({ file: files[i], error: String(e) }));
    }
  }
} finally {
  await browser.close();
  server.close();
}
process.exit(failed ? 1 : 0);
