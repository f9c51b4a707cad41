#!/usr/bin/env node
// Reads a glTF 2.0 asset with three.js's GLTFLoader, plays its first animation with an
// AnimationMixer and prints the world position of every vertex at the given times, computed as
// three.js renders them: morph targets first (the rest plus the weighted target deltas), then
// the skin (bindMatrixInverse * sum_i w_i * bone_i.matrixWorld * boneInverse_i * bindMatrix * p),
// then the mesh's matrixWorld. The per-vertex work is three's own Mesh / SkinnedMesh
// getVertexPosition, the CPU twin of its skinning and morph shaders.
//
//   node scripts/three_skinned_positions.mjs FILE.glb|FILE.gltf --times 0,0.5,1.25
//
// Prints one JSON object: {"three": revision, "file", "animation": {name, duration} or null,
// "times": [...], "meshes": [{"name", "skinned", "morph_targets", "vertex_count",
// "primitives", "primitive_spread", "positions": [[x0, y0, z0, x1, ...] per time]}]}. A mesh is
// one POSITION accessor: the primitives that share it (wirerig's parts) are one entry, in
// accessor order, and "primitive_spread" is the largest distance (m) between two primitives'
// positions of the same vertex (0 when they agree). Images are not loaded (textures are stubbed
// out); external buffers are read relative to the file. Exits 0 on success, 2 on bad usage or
// when three.js or the file cannot be read.
//
// three.js is the npm package scripts/setup.sh installs into
// <repo>/.cache/gltf-validator/node_modules/three; WIRERIG_THREE (the package folder) overrides
// that location.
import fs from 'node:fs';
import path from 'node:path';
import {fileURLToPath, pathToFileURL} from 'node:url';

const repoRoot = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const threeDir = process.env.WIRERIG_THREE ||
    path.join(repoRoot, '.cache', 'gltf-validator', 'node_modules', 'three');

function fail(message) {
  console.error(`three_skinned_positions: ${message}`);
  process.exit(2);
}

function parseArguments(args) {
  const usage = 'usage: node scripts/three_skinned_positions.mjs FILE.glb|FILE.gltf --times T1,T2,...';
  let file = null;
  let times = null;
  for (let i = 0; i < args.length; ++i) {
    if (args[i] === '--times' && i + 1 < args.length) {
      times = args[++i].split(',').map(Number);
      if (times.length === 0 || times.some((t) => !Number.isFinite(t))) fail(`bad --times: ${usage}`);
    } else if (file === null && !args[i].startsWith('-')) {
      file = path.resolve(args[i]);
    } else {
      fail(usage);
    }
  }
  if (file === null || times === null) fail(usage);
  return {file, times};
}

async function importThree() {
  // The loader imports 'three' by name, which resolves inside the package to this same module.
  const entry = path.join(threeDir, 'build', 'three.module.js');
  const loader = path.join(threeDir, 'examples', 'jsm', 'loaders', 'GLTFLoader.js');
  const meshopt = path.join(threeDir, 'examples', 'jsm', 'libs', 'meshopt_decoder.module.js');
  try {
    const THREE = await import(pathToFileURL(entry).href);
    const {GLTFLoader} = await import(pathToFileURL(loader).href);
    const {MeshoptDecoder} = await import(pathToFileURL(meshopt).href);
    return {THREE, GLTFLoader, MeshoptDecoder};
  } catch (error) {
    fail(
        `cannot load three.js from ${threeDir} (run scripts/setup.sh, or set WIRERIG_THREE): ` +
        `${error.message}`);
  }
}

function arrayBuffer(bytes) {
  return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
}

// A buffer's bytes from its URI: base64 data, or a file relative to `directory`.
function readUri(uri, directory) {
  const data = /^data:[^,]*;base64,/.exec(uri);
  if (data) return arrayBuffer(Buffer.from(uri.slice(data[0].length), 'base64'));
  return arrayBuffer(fs.readFileSync(path.resolve(directory, decodeURIComponent(uri))));
}

// A GLTFLoader plugin for Node: no images (three would decode them with the DOM), and buffers
// with a URI read here (three's FileLoader streams fetched URLs through browser-only events).
function nodeFilesPlugin(directory) {
  return (parser) => {
    const loadBuffer = parser.loadBuffer.bind(parser);
    parser.loadBuffer = (index) => {
      const uri = parser.json.buffers[index].uri;
      if (uri === undefined) return loadBuffer(index);  // the GLB's own BIN chunk
      return new Promise((resolve) => resolve(readUri(uri, directory)));
    };
    return {name: 'wirerig_node_files', loadTexture: () => Promise.resolve(null)};
  };
}

function loadGltf(GLTFLoader, MeshoptDecoder, file) {
  let bytes;
  try {
    bytes = fs.readFileSync(file);
  } catch (error) {
    fail(`cannot read ${file}: ${error.message}`);
  }
  const data = arrayBuffer(bytes);
  const loader = new GLTFLoader();
  loader.setMeshoptDecoder(MeshoptDecoder);  // EXT_meshopt_compression (wirerig bake --compress)
  loader.register(nodeFilesPlugin(path.dirname(file)));
  return new Promise((resolve, reject) => loader.parse(data, '', resolve, reject))
      .catch((error) => fail(`${file}: GLTFLoader could not read the asset: ${error?.message ?? error}`));
}

// The meshes of the scene, one per POSITION attribute (primitives sharing it grouped), in
// traversal order.
function meshesByPositions(root) {
  const groups = new Map();
  root.traverse((object) => {
    if (!object.isMesh) return;
    const key = object.geometry.attributes.position;
    if (!groups.has(key)) groups.set(key, []);
    groups.get(key).push(object);
  });
  return [...groups.values()];
}

// Every vertex's world position as three.js draws it, into `out` (x, y, z per vertex).
function worldPositions(THREE, mesh, out) {
  const v = new THREE.Vector3();
  const count = mesh.geometry.attributes.position.count;
  for (let i = 0; i < count; ++i) {
    mesh.getVertexPosition(i, v);
    v.applyMatrix4(mesh.matrixWorld);
    out[3 * i] = v.x;
    out[3 * i + 1] = v.y;
    out[3 * i + 2] = v.z;
  }
}

// Largest distance between `first`'s positions and those another primitive draws of the same
// vertices (the ones its triangles use).
function primitiveSpread(THREE, first, others) {
  const v = new THREE.Vector3();
  let spread = 0;
  for (const mesh of others) {
    const index = mesh.geometry.index;
    const count = index ? index.count : mesh.geometry.attributes.position.count;
    for (let k = 0; k < count; ++k) {
      const i = index ? index.getX(k) : k;
      mesh.getVertexPosition(i, v);
      v.applyMatrix4(mesh.matrixWorld);
      const d = Math.hypot(v.x - first[3 * i], v.y - first[3 * i + 1], v.z - first[3 * i + 2]);
      spread = Math.max(spread, d);
    }
  }
  return spread;
}

const {file, times} = parseArguments(process.argv.slice(2));
const {THREE, GLTFLoader, MeshoptDecoder} = await importThree();
const gltf = await loadGltf(GLTFLoader, MeshoptDecoder, file);
const scene = gltf.scene;
const clip = gltf.animations.length > 0 ? gltf.animations[0] : null;
const mixer = new THREE.AnimationMixer(scene);
const action = clip ? mixer.clipAction(clip) : null;
if (action) action.play();

const groups = meshesByPositions(scene);
const meshes = groups.map((group) => ({
  name: group[0].name,
  skinned: group[0].isSkinnedMesh === true,
  morph_targets: (group[0].geometry.morphAttributes.position ?? []).length,
  vertex_count: group[0].geometry.attributes.position.count,
  primitives: group.length,
  primitive_spread: 0,
  positions: [],
}));
for (const t of times) {
  if (action) {
    // mixer.update(0) evaluates the clip at exactly action.time (no looping or clamping).
    action.time = t;
    mixer.update(0);
  }
  scene.updateMatrixWorld(true);
  groups.forEach((group, m) => {
    const positions = new Array(3 * meshes[m].vertex_count);
    worldPositions(THREE, group[0], positions);
    meshes[m].positions.push(positions);
    meshes[m].primitive_spread =
        Math.max(meshes[m].primitive_spread, primitiveSpread(THREE, positions, group.slice(1)));
  });
}

process.stdout.write(JSON.stringify({
  three: THREE.REVISION,
  file,
  animation: clip ? {name: clip.name, duration: clip.duration} : null,
  times,
  meshes,
}));
process.stdout.write('\n');
