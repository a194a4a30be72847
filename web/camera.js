// The automatic camera of `dqskin render` (lib/draw/camera.cpp, frame_camera), so that a frame here and
// the same frame there are seen from the same place: it looks at the centre of the clip's bounding box from
// a yaw/pitch direction and fits the box's eight corners into the view with a small margin. JavaScript
// numbers are doubles, as the C++ computes in.
import * as THREE from 'three';

// options: { yaw, pitch, fov (degrees), distance (or undefined), ortho }; box: { min: [x,y,z], max: [x,y,z] }.
export function frameCamera(box, options, aspect) {
  const lo = new THREE.Vector3(...box.min), hi = new THREE.Vector3(...box.max);
  const center = lo.clone().add(hi).multiplyScalar(0.5);
  const radius = Math.max(0.5 * hi.distanceTo(lo), 1e-6);
  const yaw = THREE.MathUtils.degToRad(options.yaw), pitch = THREE.MathUtils.degToRad(options.pitch);
  // From the centre towards the eye: yaw 0, pitch 0 looks from +Z at the model's front.
  const back = new THREE.Vector3(Math.sin(yaw) * Math.cos(pitch), Math.sin(pitch), Math.cos(yaw) * Math.cos(pitch));
  const worldUp = Math.abs(back.y) > 0.999 ? new THREE.Vector3(0, 0, -1) : new THREE.Vector3(0, 1, 0);
  const right = new THREE.Vector3().crossVectors(worldUp, back).normalize();
  const up = new THREE.Vector3().crossVectors(back, right);

  const margin = 1.08;
  const tanY = Math.tan(THREE.MathUtils.degToRad(options.fov) / 2), tanX = tanY * aspect;
  let fit = 0, halfX = 0, halfY = 0;
  for (let corner = 0; corner < 8; ++corner) {
    const c = new THREE.Vector3(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
    const d = c.sub(center);
    const x = Math.abs(d.dot(right)) * margin, y = Math.abs(d.dot(up)) * margin, z = d.dot(back);
    fit = Math.max(fit, z + x / tanX, z + y / tanY);
    halfX = Math.max(halfX, x);
    halfY = Math.max(halfY, y);
  }
  const distance = options.distance ?? (options.ortho ? 2 * radius : fit);
  const near = Math.max(distance - 1.5 * radius, 1e-3 * radius);
  const far = Math.max(distance + 1.5 * radius, near * 2);

  let camera;
  if (options.ortho) {
    halfX = Math.max(halfX, halfY * aspect, 1e-6);
    halfY = halfX / aspect;
    camera = new THREE.OrthographicCamera(-halfX, halfX, halfY, -halfY, near, far);
  } else {
    camera = new THREE.PerspectiveCamera(options.fov, aspect, near, far);
  }
  // glm::lookAt and Matrix4.lookAt build the same basis from the same eye, target and up.
  camera.position.copy(center).addScaledVector(back, distance);
  camera.up.copy(up);
  camera.lookAt(center);
  camera.updateMatrixWorld();
  return camera;
}
