// Reads a dqskin texture (OpenEXR, float or half, any lossless compression) into a float DataTexture with
// three.js's EXRLoader. EXRLoader hands the rows bottom-up (OpenGL's convention); they are put back in
// the file's order here, so that row 0 of the texture is the file's first row, as glTF images are
// uploaded (flipY false): a glTF texture coordinate then addresses the texel it names in the file.
import * as THREE from 'three';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';

// options.fault === 'row-order' keeps EXRLoader's order: a deliberately wrong decode for the tests.
export async function loadExrTexture(url, options = {}) {
  if (!url.endsWith('.exr'))
    throw new Error(`${url}: the player reads OpenEXR textures only (a browser decodes PNG to 8 bits per channel)`);
  const loader = new EXRLoader();
  loader.setDataType(THREE.FloatType);
  const data = await loader.loadAsync(url);
  const { width, height } = data.image;
  const rows = data.image.data;
  const stride = width * 4;
  const ordered = new Float32Array(rows.length);
  for (let y = 0; y < height; ++y) {
    const from = options.fault === 'row-order' ? y : height - 1 - y;
    ordered.set(rows.subarray(from * stride, (from + 1) * stride), y * stride);
  }
  const texture = new THREE.DataTexture(ordered, width, height, THREE.RGBAFormat, THREE.FloatType);
  // Texels are values, not colours: no filtering between them (float filtering is an extension), no mips.
  texture.minFilter = texture.magFilter = THREE.NearestFilter;
  texture.generateMipmaps = false;
  texture.flipY = false;
  texture.colorSpace = THREE.NoColorSpace;
  texture.needsUpdate = true;
  return texture;
}
