// The `morph` output (animation.glb) as any three.js application shows it: GLTFLoader, the glTF
// animation on an AnimationMixer, and three.js's own morph-target code (its shader chunks
// morphtarget_pars_vertex, morphnormal_vertex and morphtarget_vertex). Only the colour is ours: the
// material shows world-space normals as `dqskin render --shade normals` does, where a stock material
// would light the mesh.
import * as THREE from 'three';
import { normalsFragment } from './shading.js';

const vertex = /* glsl */ `
#include <common>
#include <morphtarget_pars_vertex>
out vec3 world_position;
out vec3 world_normal;
void main() {
  #include <beginnormal_vertex>
  #include <morphinstance_vertex>
  #include <morphnormal_vertex>
  #include <begin_vertex>
  #include <morphtarget_vertex>
  // The inverse transpose, right for any node scale (KHR_mesh_quantization puts the grid's on the node).
  world_normal = transpose(inverse(mat3(modelMatrix))) * objectNormal;
  vec4 world = modelMatrix * vec4(transformed, 1.0);
  world_position = world.xyz;
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

function normalsMaterial(geometry) {
  // GLSL ES 3.00, so that the fragment stage is the one our own materials share.
  return new THREE.ShaderMaterial({
    glslVersion: THREE.GLSL3,
    vertexShader: vertex,
    fragmentShader: normalsFragment,
    uniforms: { has_normals: { value: geometry.getAttribute('normal') !== undefined } },
    side: THREE.DoubleSide,
  });
}

// gltf: GLTFLoader's result; keepMaterials: draw the file's own materials (lit by the caller) instead of
// normals. Returns { object, setTime(seconds) }.
export function morphView(gltf, clipName, keepMaterials = false) {
  const object = gltf.scene;
  object.traverse((node) => {
    if (node.isMesh && !keepMaterials) node.material = normalsMaterial(node.geometry);
  });
  const clip = gltf.animations.find((a) => a.name === clipName) ?? gltf.animations[0];
  if (!clip) throw new Error('animation.glb has no animation');
  const mixer = new THREE.AnimationMixer(object);
  const action = mixer.clipAction(clip);
  // Once and clamped: the last frame's time is the clip's end, which a repeating action wraps to 0.
  action.setLoop(THREE.LoopOnce, 1);
  action.clampWhenFinished = true;
  action.play();
  return {
    object,
    setTime(seconds) {
      action.reset();
      action.play();
      mixer.setTime(seconds);
    },
  };
}
