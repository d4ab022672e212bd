// Loads a glTF recording (.glb) with three.js's GLTFLoader, as a web viewer would, plays its
// animation with an AnimationMixer to the last frame, and prints what three.js sees: each
// mesh (vertices, morph targets), the clip (duration, tracks) and, with the state file of the
// same run (`simulate --record FILE.glb --out STATE.json`), how far the first object's vertices
// played to the last frame are from the simulated state (a cloth's; a rope's mesh is its tube).
//
//   npm install three            (in any folder; THREE_DIR names its node_modules/three)
//   node scripts/check-gltf-three.mjs FILE.glb [STATE.json]
//
// Exits 1 when three.js cannot load the file or the played vertices are off by more than 1e-5 m.
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [file, stateFile] = process.argv.slice(2);
if (!file) {
  console.error('usage: node scripts/check-gltf-three.mjs FILE.glb [STATE.json]');
  process.exit(2);
}
const dir = process.env.THREE_DIR ?? path.join(process.cwd(), 'node_modules', 'three');
const load = (p) => import(pathToFileURL(path.join(dir, p)).href);
let THREE, GLTFLoader;
try {
  THREE = await load('build/three.module.js');
  ({ GLTFLoader } = await load('examples/jsm/loaders/GLTFLoader.js'));
} catch (e) {
  console.error(`three.js not found in ${dir} (npm install three, or set THREE_DIR): ${e.message}`);
  process.exit(2);
}

const bytes = readFileSync(file);
const gltf = await new Promise((resolve, reject) =>
  new GLTFLoader().parse(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length), '', resolve, reject),
).catch((e) => {
  console.error(`${file}: three.js could not load it: ${e.message ?? e}`);
  process.exit(1);
});

console.log(`three.js r${THREE.REVISION}: ${file}`);
const meshes = [];
gltf.scene.traverse((o) => {
  if (o.isMesh) meshes.push(o);
});
for (const m of meshes) {
  const g = m.geometry;
  const targets = g.morphAttributes.position?.length ?? 0;
  console.log(`  mesh ${m.name}: ${g.attributes.position.count} vertices, ${g.index ? g.index.count / 3 : 0} triangles, ${targets} morph targets`);
}
const clip = gltf.animations[0];
if (!clip) {
  console.log('  no animation');
  process.exit(0);
}
console.log(`  animation: ${clip.duration.toFixed(4)} s, ${clip.tracks.length} tracks (${[...new Set(clip.tracks.map((t) => t.name.split('.').pop()))].join(', ')})`);

// Played to the last frame: a mesh's vertex is its base plus each target times its weight.
// (Played once and held at its end: looping, the clip's end is its start again.)
const mixer = new THREE.AnimationMixer(gltf.scene);
const action = mixer.clipAction(clip);
action.setLoop(THREE.LoopOnce, 1);
action.clampWhenFinished = true;
action.play();
mixer.setTime(clip.duration);
const played = (m) => {
  const g = m.geometry;
  const base = g.attributes.position.array;
  const out = Float32Array.from(base);
  const targets = g.morphAttributes.position ?? [];
  const weights = m.morphTargetInfluences ?? [];
  targets.forEach((t, k) => {
    const w = weights[k] ?? 0;
    if (w === 0) return;
    for (let i = 0; i < out.length; i++) out[i] += w * t.array[i];
  });
  return out;
};
for (const m of meshes.filter((m) => !m.geometry.morphAttributes.position)) {
  if (clip.tracks.some((t) => t.name.startsWith(`${m.name}.`) || t.name.startsWith(`${m.parent?.name}.`))) {
    const p = new THREE.Vector3();
    m.getWorldPosition(p);
    console.log(`  ${m.name}: moved by (${p.x.toFixed(4)}, ${p.y.toFixed(4)}, ${p.z.toFixed(4)}) m at the last frame`);
  }
}
if (stateFile) {
  const state = JSON.parse(readFileSync(stateFile, 'utf8'));
  const want = state.objects[0].positions.flat();
  const mesh = meshes.find((m) => m.geometry.morphAttributes.position);
  if (mesh.geometry.attributes.position.count * 3 !== want.length) {
    // A rope's mesh is its tube, not its nodes: nothing to compare with the state.
    console.log(`  ${mesh.name}: its mesh is not its particles (a rope's tube): not compared with the state`);
    process.exit(0);
  }
  const got = played(mesh);
  let worst = 0;
  for (let i = 0; i < want.length; i++) worst = Math.max(worst, Math.abs(got[i] - want[i]));
  console.log(`  ${mesh.name} played to ${clip.duration.toFixed(4)} s: ${worst.toExponential(2)} m from the simulated state`);
  if (!(worst <= 1e-5)) process.exit(1);
}
