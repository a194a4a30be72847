// dqskin's `mat3x4` bone texture (docs/formats.md, "Bone textures") played by PlayCanvas's own GPU
// skinning. PlayCanvas's released package has no reader of a baked multi-frame bone texture: its skinning
// chunk (skinVS, getBoneMatrix / getSkinMatrix) reads one pose, joint j's three texels at the linear
// index 3j of `texture_poseMap` (row index / width, column index mod width), the rows of the joint's
// affine matrix, which SkinInstance.updateMatrixPalette writes from the bones' world matrices each frame.
// One row of dqskin's mat3x4 texture (frame f: joint j at texels 3j .. 3j + 2) is exactly that palette's
// contents, so this page plays the clip by handing PlayCanvas row f as its palette: the SkinInstance's
// updateMatrixPalette copies the frame's row into PlayCanvas's own matrixPalette and uploads its own
// bone texture, instead of computing it from bones. The vertex shader includes PlayCanvas's transformCoreVS
// (with SKIN defined by PlayCanvas for a skinned mesh instance, it includes skinVS: the decode and the
// weighted sum) and draws normals as `dqskin render --shade normals`, with dqskin render's camera.
import * as pc from 'playcanvas';
import { readBonesMesh } from './glb_mesh.js';
import { cameraMatrices, canvasSize, clipEntry, fault, finish, loadBones, normalsFragmentBody, openClip, showError } from './page.js';

const vertexGLSL = /* glsl */ `
#include "transformCoreVS"
#ifdef HAS_NORMALS
attribute vec3 vertex_normal;
#endif
uniform mat4 dqskin_view;
uniform mat4 dqskin_projection;
varying vec3 vPositionW;
varying vec3 vNormalW;
void main(void) {
  mat4 model = getModelMatrix();
  vec4 p = model * vec4(getLocalPosition(vertex_position.xyz), 1.0);
  vPositionW = p.xyz;
#ifdef HAS_NORMALS
  // The normal by the cofactor of the blended matrix, as dqskin's LBS (det · inverse transpose).
  mat3 a = mat3(model);
  vNormalW = mat3(cross(a[1], a[2]), cross(a[2], a[0]), cross(a[0], a[1])) * vertex_normal;
#else
  vNormalW = vec3(0.0);
#endif
  gl_Position = dqskin_projection * dqskin_view * p;
}`;

const fragmentGLSL = /* glsl */ `
precision highp float;
varying vec3 vPositionW;
varying vec3 vNormalW;
${normalsFragmentBody}
void main(void) {
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
  const app = new pc.Application(canvas, {
    graphicsDeviceOptions: { deviceTypes: [pc.DEVICETYPE_WEBGL2], antialias: true, preserveDrawingBuffer: true, alpha: false },
  });
  app.setCanvasFillMode(pc.FILLMODE_NONE, width, height);
  app.setCanvasResolution(pc.RESOLUTION_FIXED, width, height);
  const { view, projection } = await cameraMatrices(clip, width / height);

  // PlayCanvas needs a camera to render the layers; the material projects with dqskin's camera instead.
  const camera = new pc.Entity('camera');
  camera.addComponent('camera', {
    clearColor: new pc.Color(0.2, 0.2, 0.2, 1),  // dqskin render's --background 0.2 (sRGB), as it is
    gammaCorrection: pc.GAMMA_NONE,
    toneMapping: pc.TONEMAP_LINEAR,
  });
  app.root.addChild(camera);

  const primitives = await readBonesMesh(`${clip.folder}/bones_mesh.glb`);
  const textures = new Map();
  const skins = [];
  let frame = 0;
  const entity = new pc.Entity('bones_mesh');
  const meshInstances = [];
  for (const p of primitives) {
    if (!textures.has(p.bones)) textures.set(p.bones, await loadBones(clip.folder, p.bones, 'mat3x4', wrong));
    const bones = textures.get(p.bones);
    // The clip's frames in the texture: all of it, or its range in a --combine-clips texture.
    const first = clipEntry(bones.side, clip.clip, `${p.bones}.json`, wrong).first_frame;
    if (p.joints.length > 1) throw new Error('bones_mesh.glb: PlayCanvas skins with at most 4 influences');
    const count = p.positions.length / 3;
    const mesh = new pc.Mesh(app.graphicsDevice);
    mesh.setPositions(p.positions);
    if (p.normals) mesh.setNormals(p.normals);
    mesh.setVertexStream(pc.SEMANTIC_BLENDINDICES, p.joints[0], 4, count, pc.TYPE_FLOAT32);
    mesh.setVertexStream(pc.SEMANTIC_BLENDWEIGHT, p.weights[0], 4, count, pc.TYPE_FLOAT32);
    mesh.setIndices(p.indices);
    mesh.update(pc.PRIMITIVE_TRIANGLES);

    // A skin of the texture's joints (identity inverse binds: the palette already holds world · inverseBind).
    const joints = bones.side.joints.length;
    const skin = new pc.Skin(app.graphicsDevice, Array.from({ length: joints }, () => new pc.Mat4()),
      bones.side.joints.map((name, j) => `${j}:${name}`));
    const instance = new pc.SkinInstance(skin);
    // PlayCanvas writes the palette from the bones' world matrices here; this page writes frame f's row.
    instance.updateMatrices = () => {};
    instance.updateMatrixPalette = function updateMatrixPalette() {
      const at = 4 * bones.width * (first + frame);
      const row = bones.data.subarray(at, at + 12 * joints);
      this.matrixPalette.set(row);
      this.uploadBones(app.graphicsDevice);
    };
    skins.push(instance);

    const material = new pc.ShaderMaterial({
      uniqueName: 'dqskin_normals',
      vertexGLSL,
      fragmentGLSL,
      attributes: p.normals ? { vertex_position: pc.SEMANTIC_POSITION, vertex_normal: pc.SEMANTIC_NORMAL }
        : { vertex_position: pc.SEMANTIC_POSITION },
    });
    if (p.normals) material.setDefine('HAS_NORMALS', true);
    material.cull = pc.CULLFACE_NONE;
    material.setParameter('dqskin_view', new Float32Array(view));
    material.setParameter('dqskin_projection', new Float32Array(projection));
    material.update();
    const meshInstance = new pc.MeshInstance(mesh, material, entity);
    meshInstance.skinInstance = instance;
    // PlayCanvas culls a skinned mesh by its bones' bounds; this one has no bones to measure.
    meshInstance.cull = false;
    meshInstances.push(meshInstance);
  }
  entity.addComponent('render', { meshInstances });
  app.root.addChild(entity);

  const show = (index) => {
    frame = index;
    for (const s of skins) s._dirty = true;
  };
  if (clip.index !== undefined) {
    show(clip.index);
    app.render();
    finish(canvas);
    return;
  }
  const fps = clip.clip.fps || 30;
  const start = performance.now();
  app.on('update', () => show(Math.floor((performance.now() - start) / 1000 * fps) % clip.frames.length));
  app.start();
}

main().catch((e) => showError('PlayCanvas', e));
