// The 3D view: a plantarch GLB scene (z up in plantarch, y up here: the file's root node turns
// it) under an orbit camera, coloured as built or by a label (labels.js).
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { colorScheme, readPropertyTable } from './labels.js';

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.outputColorSpace = THREE.SRGBColorSpace;
    container.append(this.renderer.domElement);

    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xe9eef2);
    this.scene.add(new THREE.HemisphereLight(0xf4f8ff, 0x8a7f6a, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 2.0);
    sun.position.set(3, 6, 4);
    this.scene.add(sun);
    this.grid = new THREE.GridHelper(10, 20, 0xb7c0c8, 0xd3d9de);
    this.grid.position.y = -0.002; // under a ground at z = 0, not through it
    this.scene.add(this.grid);

    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 500);
    this.camera.position.set(2.5, 1.8, 2.5);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = true;
    this.controls.target.set(0, 0.3, 0);

    this.model = null;
    this.table = null;
    this.mode = 'natural';
    this.triangles = 0;
    this.onLegend = () => {};

    // Frames are drawn on demand: when the camera moves (and while its damping settles),
    // the scene changes or the canvas is resized; an idle view costs nothing.
    this.frames = 0;
    this.framePending = false;
    this.controls.addEventListener('change', () => this.requestRender());
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  /** Draws one frame at the next animation frame (once, however often it is asked). */
  requestRender() {
    if (this.framePending) return;
    this.framePending = true;
    requestAnimationFrame(() => {
      this.framePending = false;
      // update() moves a damped camera on and, while it still moves, fires 'change' again.
      this.controls.update();
      this.renderer.render(this.scene, this.camera);
      this.frames++;
    });
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.container;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  /** Loads a GLB (replacing the scene shown); frames the camera on the first load. */
  async load(url, { frame = false } = {}) {
    const gltf = await new GLTFLoader().loadAsync(url);
    const table = await readPropertyTable(gltf);
    if (this.model) {
      this.scene.remove(this.model);
      disposeTree(this.model);
    }
    this.model = gltf.scene;
    this.table = table;
    this.triangles = 0;
    this.model.traverse((o) => {
      if (!o.isMesh) return;
      const g = o.geometry;
      this.triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
      o.userData.naturalMaterial = o.material;
    });
    this.scene.add(this.model);
    this.applyColors();
    if (frame) this.frame();
    this.requestRender();
    return { triangles: this.triangles };
  }

  clear() {
    if (!this.model) return;
    this.scene.remove(this.model);
    disposeTree(this.model);
    this.model = null;
    this.table = null;
    this.triangles = 0;
    this.onLegend(null);
    this.requestRender();
  }

  /** Points the camera at the plants (the whole scene when it has none). */
  frame() {
    if (!this.model) return;
    // Plant nodes carry their plant ID in their extras; the ground and obstacles do not.
    const box = new THREE.Box3();
    this.model.updateMatrixWorld(true);
    this.model.traverse((o) => {
      if (o.userData?.plantID !== undefined) box.expandByObject(o);
    });
    if (box.isEmpty()) box.setFromObject(this.model);
    if (box.isEmpty()) return;
    const size = box.getSize(new THREE.Vector3());
    const center = box.getCenter(new THREE.Vector3());
    const radius = Math.max(size.length() / 2, 0.05);
    const distance = (radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2))) * 0.8;
    const direction = new THREE.Vector3(1, 0.65, 1.15).normalize();
    this.controls.target.copy(center);
    this.camera.position.copy(center).addScaledVector(direction, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    const extent = Math.max(size.x, size.z, 1);
    this.grid.scale.setScalar(Math.ceil(extent * 1.5) / 10);
    this.requestRender();
  }

  setMode(mode) {
    this.mode = mode;
    this.applyColors();
    this.requestRender();
  }

  applyColors() {
    if (!this.model) return;
    if (this.mode === 'natural' || !this.table) {
      this.model.traverse((o) => {
        if (o.isMesh) o.material = o.userData.naturalMaterial;
      });
      this.onLegend(null);
      return;
    }
    const scheme = colorScheme(this.mode, this.table);
    const material = new THREE.MeshStandardMaterial({
      vertexColors: true,
      side: THREE.DoubleSide,
      roughness: 0.85,
      metalness: 0,
    });
    const color = new THREE.Color();
    this.model.traverse((o) => {
      if (!o.isMesh) return;
      const feature = o.geometry.attributes._feature_id_0;
      if (!feature) return;
      const n = feature.count;
      const colors = new Float32Array(n * 3);
      let lastRow = -1;
      for (let i = 0; i < n; i++) {
        const row = feature.getX(i);
        if (row !== lastRow) {
          const [r, g, b] = scheme.color(row);
          color.setRGB(r / 255, g / 255, b / 255, THREE.SRGBColorSpace);
          lastRow = row;
        }
        colors[3 * i] = color.r;
        colors[3 * i + 1] = color.g;
        colors[3 * i + 2] = color.b;
      }
      o.geometry.setAttribute('color', new THREE.BufferAttribute(colors, 3));
      o.material = material;
    });
    this.onLegend(scheme);
  }

  /** The labels of the organ under a point of the canvas (client coordinates), or null. */
  pick(clientX, clientY) {
    if (!this.model || !this.table) return null;
    const rect = this.renderer.domElement.getBoundingClientRect();
    const pointer = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    const ray = new THREE.Raycaster();
    ray.setFromCamera(pointer, this.camera);
    const hit = ray.intersectObject(this.model, true)[0];
    const feature = hit?.object.geometry.attributes._feature_id_0;
    if (!hit || !feature) return null;
    const row = feature.getX(hit.face.a);
    const c = this.table.columns;
    const info = {
      plant: c.plant?.[row],
      organ: this.table.organNames[c.organ?.[row]] ?? 'unlabelled',
      leaf: c.leaf?.[row],
      rank: c.rank?.[row],
      age: c.age?.[row],
    };
    // The physiology's columns, where this object has a value (not the column's noData).
    for (const name of ['absorbed_par', 'carbohydrate_concentration']) {
      const v = c[name]?.[row];
      if (Number.isFinite(v) && v !== this.table.noData?.[name]) info[name] = v;
    }
    return info;
  }
}

function disposeTree(root) {
  root.traverse((o) => {
    if (!o.isMesh) return;
    o.geometry.dispose();
    const materials = [o.material, o.userData.naturalMaterial].flat();
    for (const m of materials) m?.dispose?.();
  });
}
