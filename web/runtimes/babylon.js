// dqskin's `mat4` bone texture (docs/formats.md, "Bone textures") played by Babylon.js's baked vertex
// animation, as a Babylon.js application plays a texture made by its own VertexAnimationBaker: the EXR read
// by Babylon's own EXR decoder; the mesh with a skeleton of the skin's joints (only so that Babylon
// declares the influences; its bones are never posed); a BakedVertexAnimationManager holding the texture
// the baker makes of the texels (textureFromBakedVertexData: RGBA float, (bones + 1) · 4 texels wide, one
// row per frame, nearest); the frame from the manager's time and setAnimationParameters. The vertex shader
// is ours only in what it does with the result: it includes Babylon's own bonesDeclaration,
// bakedVertexAnimationDeclaration (readMatrixFromRawSamplerVAT) and bakedVertexAnimation (the frame from
// the time, the weighted sum of the joints' matrices into finalWorld) chunks, then draws normals as
// `dqskin render --shade normals`, with the camera `dqskin render` frames the clip with.
import { Engine } from '@babylonjs/core/Engines/engine.js';
import { Scene } from '@babylonjs/core/scene.js';
import { Mesh } from '@babylonjs/core/Meshes/mesh.js';
import { VertexData } from '@babylonjs/core/Meshes/mesh.vertexData.js';
import { VertexBuffer } from '@babylonjs/core/Buffers/buffer.js';
import { ShaderMaterial } from '@babylonjs/core/Materials/shaderMaterial.js';
import { Skeleton } from '@babylonjs/core/Bones/skeleton.js';
import { Bone } from '@babylonjs/core/Bones/bone.js';
import { Matrix } from '@babylonjs/core/Maths/math.vector.js';
import { Color4 } from '@babylonjs/core/Maths/math.color.js';
import { FreeCamera } from '@babylonjs/core/Cameras/freeCamera.js';
import { Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { BakedVertexAnimationManager } from '@babylonjs/core/BakedVertexAnimation/bakedVertexAnimationManager.js';
import { VertexAnimationBaker } from '@babylonjs/core/BakedVertexAnimation/vertexAnimationBaker.js';
import { ReadExrDataAsync } from '@babylonjs/core/Materials/Textures/Loaders/exrTextureLoader.js';
import { ExrLoaderGlobalConfiguration } from '@babylonjs/core/Materials/Textures/Loaders/EXR/exrLoader.configuration.js';
// The shader chunks the material includes (they register themselves in Babylon's ShaderStore).
import '@babylonjs/core/Shaders/ShadersInclude/bonesDeclaration.js';
import '@babylonjs/core/Shaders/ShadersInclude/bakedVertexAnimationDeclaration.js';
import '@babylonjs/core/Shaders/ShadersInclude/bakedVertexAnimation.js';
import { readBonesMesh } from './glb_mesh.js';
import { cameraMatrices, canvasSize, clipEntry, fault, finish, loadBones, normalsFragmentBody, openClip, showError } from './page.js';

// Babylon's EXR reader loads its zlib decoder (fflate) as a script from a CDN for ZIP-compressed files; the
// same version, installed by scripts/install/node_tools.sh, comes from disk here.
ExrLoaderGlobalConfiguration.FFLATEUrl = '/node_modules/fflate/umd/index.js';

// The EXR as Babylon.js reads it (ReadExrDataAsync: the decoder its .exr texture loader uses, float
// output): { data, width, height } with row 0 the texel row 0 Babylon uploads.
async function decodeExrWithBabylon(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  const { data, width, height } = await ReadExrDataAsync(await response.arrayBuffer());
  if (!data) throw new Error(`${url}: Babylon.js could not read it`);
  return { data, width, height };
}

const vertexSource = /* glsl */ `
precision highp float;
attribute vec3 position;
#ifdef HAS_NORMALS
attribute vec3 normal;
#endif
#include<bonesDeclaration>
#include<bakedVertexAnimationDeclaration>
uniform mat4 world;
uniform mat4 dqskinView, dqskinProjection;
varying vec3 vPositionW;
varying vec3 vNormalW;
void main() {
  mat4 finalWorld = world;
#include<bakedVertexAnimation>
  vec4 p = finalWorld * vec4(position, 1.0);
  vPositionW = p.xyz;
#ifdef HAS_NORMALS
  // The normal by the cofactor of the blended matrix, as dqskin's LBS (det · inverse transpose).
  mat3 a = mat3(finalWorld);
  vNormalW = mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1])) * normal;
#else
  vNormalW = vec3(0.0);
#endif
  gl_Position = dqskinProjection * dqskinView * p;
}`;

const fragmentSource = /* glsl */ `
precision highp float;
varying vec3 vPositionW;
varying vec3 vNormalW;
${normalsFragmentBody}
void main() {
#ifdef HAS_NORMALS
  gl_FragColor = normals_colour(vPositionW, vNormalW, true);
#else
  gl_FragColor = normals_colour(vPositionW, vNormalW, false);
#endif
}`;

async function main() {
  const wrong = fault();
  const clip = await openClip();
  const [width, height] = canvasSize();
  const canvas = document.getElementById('view');
  canvas.width = width;
  canvas.height = height;
  canvas.style.width = `${width}px`;
  canvas.style.height = `${height}px`;
  const engine = new Engine(canvas, true, { preserveDrawingBuffer: true, stencil: false, adaptToDeviceRatio: false });
  if (engine.webGLVersion < 2) throw new Error('Babylon.js found no WebGL2');
  const scene = new Scene(engine);
  // dqskin render's --background 0.2 (sRGB), written as it is: no colour management on this path.
  scene.clearColor = new Color4(0.2, 0.2, 0.2, 1);
  // Babylon needs an active camera to render; the material projects with dqskin's camera instead.
  scene.activeCamera = new FreeCamera('unused', new Vector3(0, 0, -1), scene);
  const { view, projection } = await cameraMatrices(clip, width / height);

  const primitives = await readBonesMesh(`${clip.folder}/bones_mesh.glb`);
  const managers = new Map();  // bone texture name → BakedVertexAnimationManager
  for (const [i, p] of primitives.entries()) {
    if (!managers.has(p.bones)) {
      const bones = await loadBones(clip.folder, p.bones, 'mat4', wrong, decodeExrWithBabylon);
      // The skeleton the baker would have baked: one bone per joint, and so (bones + 1) · 4 texels a row.
      const skeleton = new Skeleton(p.bones, p.bones, scene);
      for (const name of bones.side.joints) new Bone(name, skeleton, null, Matrix.Identity());
      // The texels as a Babylon.js application gives baked data to the manager: the baker's own texture.
      const manager = new BakedVertexAnimationManager(scene);
      manager.texture = new VertexAnimationBaker(scene, skeleton).textureFromBakedVertexData(bones.data);
      // The clip's frames in the texture (all of it, or its range in a --combine-clips texture, from the
      // clip table) at the clip's rate: Babylon's animation range; the time picks the frame (below).
      const entry = clipEntry(bones.side, clip.clip, `${p.bones}.json`, wrong);
      const fps = entry.fps || clip.clip.fps || 30;
      manager.setAnimationParameters(entry.first_frame, entry.first_frame + entry.frame_count - 1, 0, fps);
      managers.set(p.bones, { manager, skeleton, fps });
    }
    const { manager, skeleton } = managers.get(p.bones);
    const influences = 4 * p.joints.length;
    if (influences > 8) throw new Error('bones_mesh.glb: Babylon.js blends at most 8 influences');
    const mesh = new Mesh(`primitive${i}`, scene);
    const data = new VertexData();
    data.positions = p.positions;
    data.indices = p.indices;
    if (p.normals) data.normals = p.normals;
    data.applyToMesh(mesh);
    mesh.setVerticesData(VertexBuffer.MatricesIndicesKind, p.joints[0], false, 4);
    mesh.setVerticesData(VertexBuffer.MatricesWeightsKind, p.weights[0], false, 4);
    if (influences > 4) {
      mesh.setVerticesData(VertexBuffer.MatricesIndicesExtraKind, p.joints[1], false, 4);
      mesh.setVerticesData(VertexBuffer.MatricesWeightsExtraKind, p.weights[1], false, 4);
    }
    mesh.skeleton = skeleton;
    mesh.numBoneInfluencers = influences;
    mesh.bakedVertexAnimationManager = manager;
    // Babylon culls by the bind pose's bounds; the animated mesh is elsewhere.
    mesh.alwaysSelectAsActiveMesh = true;
    const material = new ShaderMaterial(`normals${i}`, scene, { vertexSource, fragmentSource }, {
      attributes: p.normals ? ['position', 'normal'] : ['position'],
      uniforms: ['world', 'dqskinView', 'dqskinProjection'],
      defines: p.normals ? ['#define HAS_NORMALS'] : [],
    });
    material.backFaceCulling = false;
    material.setMatrix('dqskinView', Matrix.FromArray(view));
    material.setMatrix('dqskinProjection', Matrix.FromArray(projection));
    mesh.material = material;
  }

  // The clip's frame i at time (i + ½) / fps: Babylon's bakedVertexAnimation chunk takes frame
  // from + floor(fract(time · fps / N) · N) of the range's N, so the half frame keeps the floor off a
  // rounding edge.
  const show = (index) => { for (const m of managers.values()) m.manager.time = (index + 0.5) / m.fps; };
  await scene.whenReadyAsync();
  if (clip.index !== undefined) {
    show(clip.index);
    scene.render();
    finish(canvas);
    return;
  }
  // Playing: the manager's time in seconds, looping as Babylon loops it.
  const start = performance.now();
  engine.runRenderLoop(() => {
    for (const m of managers.values()) m.manager.time = (performance.now() - start) / 1000;
    scene.render();
  });
}

main().catch((e) => showError('Babylon.js', e));
