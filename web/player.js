// The dqskin player: opens a bake folder (its manifest.json), picks an input, a clip and a path, and
// draws the clip's frames as `dqskin render --shade normals` draws them, through what a runtime would
// use: the VAT or bone texture decoded in a vertex shader, or the morph glb through three.js alone.
//
// URL parameters (all optional):
//   bake=URL      the bake folder, relative to this page (default: the folder above it, "..")
//   input=NAME    the input's folder in the bake (default: the first)
//   clip=NAME     the animation (default: the input's first)
//   path=vat|bones|morph   what to play (default: the first the clip has of morph, vat, bones)
//   frame=N       show frame N (the number in dqskin's file names) and stop; otherwise play
//   blend=CLIP:N,W   vat and bones: crossfade the clip with frame N of CLIP by weight W (0: the clip alone,
//                 1: CLIP's frame alone), as a runtime would from one texture (docs/DESIGN.md §3.10): the VAT
//                 lerps the two frames' vertices, the bone texture blends each joint's two dual quaternions
//                 before skinning. Both clips must be in the texture's clip table (bake --combine-clips, or
//                 the clip with itself). With frame= CLIP shows frame N; playing, it advances from N in step.
//   yaw, pitch, fov, distance, ortho   dqskin render's camera flags, with its defaults
//   box=x0,y0,z0,x1,y1,z1   what the camera frames (default: the clip's bounds from its vat.json, as
//                 `dqskin render` frames them, else the loaded mesh's own: the bind pose's or first frame's)
//   size=WxH      canvas pixels (default: the window); background=R,G,B (0 to 1, sRGB; default 0.2)
//   shade=material   morph only: the glb's own materials under a key and fill light, instead of normals
//   capture=1     after drawing, put the canvas as a PNG data URL into <pre id="capture"> (tests)
//   fault=row-order|lbs|offset   a deliberately wrong decode, for the tests that show a wrong decode fails
//                 (offset: a clip's frames read from the texture's first, its clip table ignored)
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { frameCamera } from './camera.js';
import { loadExrTexture } from './exr_texture.js';
import { vatMaterial } from './vat_material.js';
import { bonesMaterial } from './bones_material.js';
import { morphView } from './morph_view.js';

const params = new URLSearchParams(location.search);

function numbers(text, count, name) {
  const values = text.split(',').map(Number);
  if (values.length !== count || values.some((v) => !Number.isFinite(v)))
    throw new Error(`${name}=${text}: expected ${count} comma-separated numbers`);
  return values;
}

function number(name, fallback) {
  if (!params.has(name)) return fallback;
  const v = Number(params.get(name));
  if (!Number.isFinite(v)) throw new Error(`${name}=${params.get(name)}: not a number`);
  return v;
}

async function fetchJson(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  return response.json();
}

const gltfLoader = new GLTFLoader();

// The clip's folder and what it holds, from the manifest.
async function openBake() {
  const bake = (params.get('bake') ?? '..').replace(/\/$/, '');
  const manifest = await fetchJson(`${bake}/manifest.json`);
  const inputs = manifest.inputs ?? [];
  const input = params.has('input') ? inputs.find((i) => i.output_folder === params.get('input')) : inputs[0];
  if (!input) throw new Error(`${bake}/manifest.json: no input ${params.get('input') ?? ''}`);
  const clips = input.animations ?? [];
  const wanted = params.get('clip');
  const clip = wanted ? clips.find((c) => c.name === wanted || c.folder.endsWith(`/${wanted}`)) : clips[0];
  if (!clip)
    throw new Error(`${input.output_folder}: no clip ${wanted ?? ''} (clips: ${clips.map((c) => c.name).join(', ')})`);
  const filesIn = (folder) => new Set(manifest.outputs.map((o) => o.path).filter((p) => p.startsWith(`${folder}/`))
    .map((p) => p.slice(folder.length + 1)).filter((p) => !p.includes('/')));
  const files = filesIn(clip.folder);
  // With --combine-clips the textures are the input's, in its folder, and their clip table finds the clip.
  const inputFiles = filesIn(input.output_folder);
  const available = [];
  if (files.has('animation.glb')) available.push('morph');
  if (files.has('vat.json') || inputFiles.has('vat.json')) available.push('vat');
  if (files.has('bones_mesh.glb') || inputFiles.has('bones_mesh.glb')) available.push('bones');
  const path = params.get('path') ?? available[0];
  if (!available.includes(path))
    throw new Error(`${clip.folder}: no ${path ?? 'playable'} output (it has: ${available.join(', ') || 'none'}; ` +
      'bake with --format morph, vat or bones)');
  const own = { vat: 'vat.json', bones: 'bones_mesh.glb', morph: 'animation.glb' }[path];
  const folder = files.has(own) ? clip.folder : input.output_folder;
  const blend = params.has('blend') ? parseBlend(params.get('blend'), clips, clip, path) : undefined;
  return { folder: `${bake}/${folder}`, input, clip, files: files.has(own) ? files : inputFiles, path, blend };
}

// blend=CLIP:N,W → { clip, index (of frame N in CLIP's frames), weight, start (the index of the shown clip's
// frame= that CLIP's frame N goes with; 0 when playing) }.
function parseBlend(text, clips, shown, path) {
  const match = /^(.+):(-?\d+),([^,]+)$/.exec(text);
  if (!match) throw new Error(`blend=${text}: expected CLIP:FRAME,WEIGHT`);
  if (path === 'morph') throw new Error(`blend=${text}: the vat and bones paths crossfade; the morph glb does not`);
  const clip = clips.find((c) => c.name === match[1] || c.folder.endsWith(`/${match[1]}`));
  if (!clip) throw new Error(`blend=${text}: no clip ${match[1]} (clips: ${clips.map((c) => c.name).join(', ')})`);
  const index = clip.frame_numbers.indexOf(Number(match[2]));
  if (index < 0)
    throw new Error(`blend=${text}: ${clip.name} has frames ${clip.frame_numbers[0]} to ${clip.frame_numbers.at(-1)}`);
  const weight = Number(match[3]);
  if (!(weight >= 0 && weight <= 1)) throw new Error(`blend=${text}: the weight must be a number from 0 to 1`);
  const start = Math.max(0, params.has('frame') ? shown.frame_numbers.indexOf(Number(params.get('frame'))) : 0);
  return { clip, index, weight, start };
}

// The blended clip's frame, in its own frames, when the shown clip is at frame `index` of its own.
function blendIndex(blend, entry, index) {
  return (((blend.index + index - blend.start) % entry.frame_count) + entry.frame_count) % entry.frame_count;
}

// The blended clip's entry in a texture's clip table: it must be in the same texture as the shown clip.
function blendEntry(side, blend, file, fault) {
  try {
    return clipEntry(side, blend.clip, file, fault);
  } catch (error) {
    throw new Error(`blend=: ${error.message}; a crossfade reads both clips from one texture ` +
      '(bake --combine-clips)');
  }
}

// The clip's entry in a texture's clip table (docs/formats.md, "Several clips in one texture").
function clipEntry(side, clip, file, fault) {
  const entry = (side.clips ?? []).find((c) => c.name === clip.name);
  if (!entry) throw new Error(`${file}: no clip ${clip.name} in its clip table`);
  if (entry.frame_count !== clip.frame_times.length)
    throw new Error(`${file}: clip ${clip.name} has ${entry.frame_count} frames, the manifest ${clip.frame_times.length}`);
  return fault === 'offset' ? { ...entry, first_frame: 0 } : entry;
}

// Each path returns { object, showFrame(index, fractional), box? }.
async function vatPath(bake, fault) {
  const side = await fetchJson(`${bake.folder}/vat.json`);
  const profileFile = await fetchJson(`${bake.folder}/${side.files.profile_side_file}`);
  if (side.pages > 1) throw new Error('vat.json: the player reads single-page VATs');
  const textures = { positions: await loadExrTexture(`${bake.folder}/${side.files.positions}`, { fault }) };
  if (side.files.normals) textures.normals = await loadExrTexture(`${bake.folder}/${side.files.normals}`, { fault });
  const gltf = await gltfLoader.loadAsync(`${bake.folder}/${side.files.rest_mesh}`);
  const blend = bake.blend;
  const material = vatMaterial(side, profileFile, textures, { blend: blend !== undefined });
  gltf.scene.traverse((node) => { if (node.isMesh) node.material = material; });
  // The clip's frames in the texture, and between them no step past its last into the next clip's.
  const entry = clipEntry(side, bake.clip, 'vat.json', fault);
  material.uniforms.last_frame.value = entry.first_frame + entry.frame_count - 1;
  const other = blend && blendEntry(side, blend, 'vat.json', fault);
  if (blend) material.uniforms.blend_weight.value = blend.weight;
  return {
    object: gltf.scene,
    box: entry.bounds ?? side.bounds,
    showFrame(index, fraction = 0) {
      material.uniforms.frame.value = entry.first_frame + index + fraction;
      if (blend) material.uniforms.blend_frame.value = other.first_frame + blendIndex(blend, other, index);
    },
  };
}

async function bonesPath(bake, fault) {
  const gltf = await gltfLoader.loadAsync(`${bake.folder}/bones_mesh.glb`);
  const skins = new Map();  // texture name → { texture, side }
  const materials = [];
  const meshes = [];
  gltf.scene.traverse((node) => { if (node.isMesh) meshes.push(node); });
  for (const mesh of meshes) {
    const name = mesh.geometry.userData.bones;
    if (!name) throw new Error('bones_mesh.glb: a primitive names no bone texture');
    if (!skins.has(name)) {
      const side = await fetchJson(`${bake.folder}/${name}.json`);
      skins.set(name, { side, texture: await loadExrTexture(`${bake.folder}/${side.file}`, { fault }) });
    }
    const { side, texture } = skins.get(name);
    mesh.material = bonesMaterial(texture, side, mesh.geometry, { fault, blend: bake.blend !== undefined });
    // three.js culls by the bind-pose bounds; the skinned mesh is elsewhere.
    mesh.frustumCulled = false;
    // Row r is frame r of the texture: the clip's frames start at its first.
    const other = bake.blend && blendEntry(side, bake.blend, `${name}.json`, fault);
    if (bake.blend) mesh.material.uniforms.blend_weight.value = bake.blend.weight;
    const first = clipEntry(side, bake.clip, `${name}.json`, fault).first_frame;
    materials.push({ material: mesh.material, first, other });
  }
  const blend = bake.blend;
  return {
    object: gltf.scene,
    // Runtimes that sample bone textures show the frame at or before the time (Babylon.js floors).
    showFrame(index) {
      for (const m of materials) {
        m.material.uniforms.row.value = m.first + index;
        if (blend) m.material.uniforms.blend_row.value = m.other.first_frame + blendIndex(blend, m.other, index);
      }
    },
  };
}

async function morphPath(bake) {
  const gltf = await gltfLoader.loadAsync(`${bake.folder}/animation.glb`);
  const view = morphView(gltf, bake.clip.name, params.get('shade') === 'material');
  gltf.scene.traverse((node) => { if (node.isMesh) node.frustumCulled = false; });
  const times = bake.clip.frame_times;
  return {
    object: view.object,
    showFrame(index, fraction = 0) {
      const next = Math.min(index + 1, times.length - 1);
      view.setTime(times[index] + fraction * (times[next] - times[index]));
    },
  };
}

function objectBox(object) {
  const box = new THREE.Box3().setFromObject(object, true);
  return { min: box.min.toArray(), max: box.max.toArray() };
}

// What the camera frames: box=, else the clip's bounds over every frame as the bake measured them
// (vat.json, the box `dqskin render` frames for the same frames), else the loaded mesh's.
async function cameraBox(bake, played) {
  if (params.has('box')) {
    const b = numbers(params.get('box'), 6, 'box');
    return { min: b.slice(0, 3), max: b.slice(3) };
  }
  if (played.box) return played.box;
  if (bake.files.has('vat.json')) {
    const side = await fetchJson(`${bake.folder}/vat.json`);
    return (side.clips ?? []).find((c) => c.name === bake.clip.name)?.bounds ?? side.bounds;
  }
  return objectBox(played.object);
}

function showError(error) {
  console.error(error);
  document.body.dataset.error = error.message;
  document.getElementById('hud').hidden = false;
  document.getElementById('error').textContent = `dqskin player: ${error.message}`;
}

async function main() {
  const fault = params.get('fault') ?? undefined;
  if (fault && !['row-order', 'lbs', 'offset'].includes(fault)) throw new Error(`fault=${fault}: row-order, lbs or offset`);
  const bake = await openBake();
  const paths = { vat: vatPath, bones: bonesPath, morph: morphPath };
  const played = await paths[bake.path](bake, fault);

  const [width, height] = params.has('size') ? numbers(params.get('size').replace('x', ','), 2, 'size')
    : [window.innerWidth, window.innerHeight];
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  const resize = (w, h) => {
    renderer.setSize(w, h, false);
    canvas.style.width = `${w}px`;
    canvas.style.height = `${h}px`;
  };
  resize(width, height);
  // dqskin render's --background is sRGB (default 0.2). Our shaders write sRGB-encoded values as dqskin's
  // PNG writer does, so colour management is off and the value goes out as it is; the glb's own materials
  // (shade=material) are colour-managed, lit as a plain viewer lights them.
  const background = params.has('background') ? numbers(params.get('background'), 3, 'background') : [0.2, 0.2, 0.2];
  const scene = new THREE.Scene();
  scene.add(played.object);
  const lit = params.get('shade') === 'material';
  if (lit && bake.path !== 'morph') throw new Error('shade=material: only the morph path carries materials');
  THREE.ColorManagement.enabled = lit;
  renderer.outputColorSpace = lit ? THREE.SRGBColorSpace : THREE.LinearSRGBColorSpace;
  renderer.setClearColor(new THREE.Color().setRGB(...background, lit ? THREE.SRGBColorSpace : THREE.LinearSRGBColorSpace), 1);
  if (lit) {
    scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 2));
    const key = new THREE.DirectionalLight(0xffffff, 2);
    key.position.set(1, 2, 3);
    scene.add(key);
  }
  const frames = bake.clip.frame_numbers;
  played.showFrame(0);
  const box = await cameraBox(bake, played);
  const view = {
    yaw: number('yaw', 35), pitch: number('pitch', 20), fov: number('fov', 35),
    distance: params.has('distance') ? number('distance') : undefined, ortho: params.get('ortho') === '1',
  };
  let camera = frameCamera(box, view, width / height);

  if (params.has('frame')) {
    const index = frames.indexOf(Number(params.get('frame')));
    if (index < 0) throw new Error(`frame=${params.get('frame')}: the clip has frames ${frames[0]} to ${frames[frames.length - 1]}`);
    played.showFrame(index);
    renderer.render(scene, camera);
    if (params.get('capture') === '1') {
      const pre = document.createElement('pre');
      pre.id = 'capture';
      pre.textContent = canvas.toDataURL('image/png');
      document.body.append(pre);
    }
    document.body.dataset.ready = 'true';
    return;
  }

  // Playing: real time, looping, with a scrubber.
  const hud = document.getElementById('hud');
  hud.hidden = false;
  document.getElementById('title').textContent = `${bake.input.output_folder} / ${bake.clip.name} · ${bake.path}`;
  const scrub = document.getElementById('scrub');
  scrub.max = String(frames.length - 1);
  const label = document.getElementById('frame');
  const button = document.getElementById('play');
  const fps = bake.clip.fps || 30;
  let playing = true, start = performance.now(), position = 0;
  button.onclick = () => {
    playing = !playing;
    button.textContent = playing ? 'pause' : 'play';
    start = performance.now() - position * 1000 / fps;
  };
  scrub.oninput = () => { position = Number(scrub.value); start = performance.now() - position * 1000 / fps; };
  if (!params.has('size'))
    window.addEventListener('resize', () => {
      resize(window.innerWidth, window.innerHeight);
      camera = frameCamera(box, view, window.innerWidth / window.innerHeight);
    });
  renderer.setAnimationLoop(() => {
    if (playing) position = ((performance.now() - start) * fps / 1000) % frames.length;
    const index = Math.floor(position);
    played.showFrame(index, position - index);
    scrub.value = String(index);
    label.textContent = `frame ${frames[index]} (${bake.clip.frame_times[index].toFixed(3)} s)`;
    renderer.render(scene, camera);
  });
}

main().catch(showError);
