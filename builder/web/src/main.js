// The builder's single-page app (work in progress: the scene panel and views follow).
import * as THREE from 'three';

const root = document.getElementById('app');
const renderer = new THREE.WebGLRenderer({ antialias: true });
root.append(renderer.domElement);
