// What the runtime pages (babylon.html, playcanvas.html) share: the URL parameters, the bake's clip and
// frame, the bone textures as float arrays, `dqskin render`'s camera, and the capture protocol of
// web/runtimes/capture.mjs. The decode itself is the runtime's own shader code, in each page.
//
// URL parameters:
//   bake=URL     the bake folder (with manifest.json); input=NAME, clip=NAME as the player's
//   frame=N      the frame to show (the number in dqskin's file names); otherwise the clip plays
//   box=x0,y0,z0,x1,y1,z1   what the camera frames (default: the clip's bounds from its vat.json)
//   yaw, pitch, fov   dqskin render's camera (defaults 35, 20, 35); size=WxH canvas pixels
//   capture=1    after drawing, put the canvas as a PNG data URL into <pre id="capture"> (tests)
//   fault=row-order|transpose|joint-order|texel-offset|clip-offset   a deliberately wrong texture read,
//                for the tests that show a wrong decode fails: the rows upside down (a wrong frame row),
//                each joint's matrix transposed (its 3×3 part for mat3x4), joint j reading joint j + 1's
//                texels, every texel read one texel to the right (an addressing off by one), or a clip of
//                a combined texture (--combine-clips) played from the texture's first frame, its clip
//                table ignored
import { loadExrTexture } from '../exr_texture.js';
import { frameCamera } from '../camera.js';

export const params = new URLSearchParams(location.search);
const faults = ['row-order', 'transpose', 'joint-order', 'texel-offset', 'clip-offset'];

export function numbers(text, count, name) {
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

export async function fetchJson(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  return response.json();
}

export function fault() {
  const f = params.get('fault') ?? undefined;
  if (f !== undefined && !faults.includes(f)) throw new Error(`fault=${f}: one of ${faults.join(', ')}`);
  return f;
}

// The clip's folder in the bake (manifest.json), its frame numbers, and the frame asked for (its index).
export async function openClip() {
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
  const files = new Set(manifest.outputs.map((o) => o.path));
  // With --combine-clips the textures are the input's, in its folder, and their clip table finds the clip.
  const folder = [clip.folder, input.output_folder].find((f) => files.has(`${f}/bones_mesh.glb`));
  if (!folder) throw new Error(`${clip.folder}: no bones_mesh.glb (bake with --format bones)`);
  const frames = clip.frame_numbers;
  let index;
  if (params.has('frame')) {
    index = frames.indexOf(Number(params.get('frame')));
    if (index < 0) throw new Error(`frame=${params.get('frame')}: the clip has frames ${frames[0]} to ${frames[frames.length - 1]}`);
  }
  return { folder: `${bake}/${folder}`, clip, frames, index, hasVat: files.has(`${folder}/vat.json`) };
}

// The clip's entry in a texture's clip table (docs/formats.md, "Several clips in one texture"): its
// first_frame is where its frames start in the texture (0 for a texture of one clip).
export function clipEntry(side, clip, file, wrong) {
  const entry = (side.clips ?? []).find((c) => c.name === clip.name);
  if (!entry) throw new Error(`${file}: no clip ${clip.name} in its clip table`);
  if (entry.frame_count !== clip.frame_numbers.length)
    throw new Error(`${file}: clip ${clip.name} has ${entry.frame_count} frames, the manifest ${clip.frame_numbers.length}`);
  return wrong === 'clip-offset' ? { ...entry, first_frame: 0 } : entry;
}

// three.js's EXRLoader (web/exr_texture.js), with the rows put back in the file's order: row 0 is the
// file's first row. For a runtime without an EXR reader of its own (PlayCanvas).
export async function decodeExrInFileOrder(url) {
  const texture = await loadExrTexture(url);
  return { data: texture.image.data, width: texture.image.width, height: texture.image.height };
}

// A bone texture (bones_skinK.json and its EXR) as { side, data: Float32Array RGBA, width, height },
// decoded by `decode` (url → { data, width, height }, row 0 the texel row 0 the runtime uploads), checked
// against the profile the page's runtime reads. A fault rewrites the texels the runtime will read (the
// runtime's shader is never changed).
export async function loadBones(folder, name, profile, wrong, decode = decodeExrInFileOrder) {
  const side = await fetchJson(`${folder}/${name}.json`);
  if (side.profile !== profile)
    throw new Error(`${name}.json: profile '${side.profile}'; this page plays --bones-profile ${profile}`);
  const { data, width, height } = await decode(`${folder}/${side.file}`);
  const t = side.texels_per_joint, joints = side.joints.length;
  if (width !== side.width || height !== side.height || width < t * joints)
    throw new Error(`${side.file}: ${width}×${height}, its side file says ${side.width}×${side.height}`);
  if (wrong === 'row-order') {  // the rows upside down: frame f reads frame N − 1 − f
    const stride = 4 * width;
    for (let top = 0, bottom = height - 1; top < bottom; ++top, --bottom) {
      const row = data.slice(top * stride, (top + 1) * stride);
      data.copyWithin(top * stride, bottom * stride, (bottom + 1) * stride);
      data.set(row, bottom * stride);
    }
  }
  for (let row = 0; row < height; ++row) {
    const at = (x, c) => 4 * (row * width + x) + c;
    if (wrong === 'transpose') {
      // texel k, channel c ↔ texel c, channel k: columns read as rows (the 3×3 part of mat3x4's rows)
      for (let j = 0; j < joints; ++j)
        for (let k = 0; k < Math.min(t, 4); ++k)
          for (let c = k + 1; c < Math.min(t, 4); ++c) {
            const a = at(t * j + k, c), b = at(t * j + c, k);
            [data[a], data[b]] = [data[b], data[a]];
          }
    } else if (wrong === 'joint-order') {
      const first = data.slice(at(0, 0), at(t, 0));
      data.copyWithin(at(0, 0), at(t, 0), at(t * joints, 0));
      data.set(first, at(t * (joints - 1), 0));
    } else if (wrong === 'texel-offset') {
      data.copyWithin(at(0, 0), at(1, 0), at(width, 0));
      data.fill(0, at(width - 1, 0), at(width, 0));
    }
  }
  return { side, data, width, height };
}

// dqskin render's camera for the clip (web/camera.js, lib/draw/camera.cpp), as column-major view and
// projection matrices (WebGL clip space), the layout both runtimes upload.
export async function cameraMatrices(clip, aspect) {
  let box;
  if (params.has('box')) {
    const b = numbers(params.get('box'), 6, 'box');
    box = { min: b.slice(0, 3), max: b.slice(3) };
  } else if (clip.hasVat) {
    const side = await fetchJson(`${clip.folder}/vat.json`);
    box = (side.clips ?? []).find((c) => c.name === clip.clip.name)?.bounds ?? side.bounds;
  } else {
    throw new Error('box= is needed: the bake has no vat.json whose bounds the camera would frame');
  }
  const camera = frameCamera(box, { yaw: number('yaw', 35), pitch: number('pitch', 20), fov: number('fov', 35) }, aspect);
  return { view: camera.matrixWorldInverse.elements, projection: camera.projectionMatrix.elements };
}

export function canvasSize() {
  return params.has('size') ? numbers(params.get('size').replace('x', ','), 2, 'size') : [window.innerWidth, window.innerHeight];
}

// After the frame is drawn: the PNG for capture.mjs, and the page marked done.
export function finish(canvas) {
  if (params.get('capture') === '1') {
    const pre = document.createElement('pre');
    pre.id = 'capture';
    pre.textContent = canvas.toDataURL('image/png');
    document.body.append(pre);
  }
  document.body.dataset.ready = 'true';
}

export function showError(runtime, error) {
  console.error(error);
  document.body.dataset.error = error.message;
  const pre = document.createElement('pre');
  pre.textContent = `dqskin ${runtime} page: ${error.message}`;
  document.body.append(pre);
}

// The fragment stage both pages use: `dqskin render --shade normals` (web/shading.js): the world-space
// unit normal as colour, 0.5 n + 0.5, sRGB-encoded as dqskin's PNG writer does, or the triangle's own
// normal where the mesh has none. GLSL ES 1.00 style, which both runtimes translate for WebGL2.
export const normalsFragmentBody = /* glsl */ `
vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
vec4 normals_colour(vec3 world_position, vec3 world_normal, bool has_normals) {
  vec3 face = cross(dFdx(world_position), dFdy(world_position));
  vec3 n = has_normals ? normalize(world_normal) : normalize(face);
  return vec4(srgb_encode(0.5 * n + 0.5), 1.0);
}`;
