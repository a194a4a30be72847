// Reads dqskin's bones_mesh.glb into plain arrays, primitive by primitive, so that each runtime builds its
// own mesh from them: the glb keeps its influences in the application-specific attributes _JOINTS_n /
// _WEIGHTS_n (glTF 2.0 §3.7.2.1: no skin, so that a viewer does not skin it), which the runtimes' glTF
// loaders do not read. Only what dqskin writes there is read: tightly packed or strided accessors, no sparse
// accessors, triangle lists.
const componentArrays = { 5121: Uint8Array, 5123: Uint16Array, 5125: Uint32Array, 5126: Float32Array };
const componentCounts = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };

function parseGlb(buffer, url) {
  const view = new DataView(buffer);
  if (buffer.byteLength < 20 || view.getUint32(0, true) !== 0x46546c67)
    throw new Error(`${url}: not a binary glTF`);
  let json, bin;
  for (let at = 12; at + 8 <= buffer.byteLength;) {
    const length = view.getUint32(at, true), type = view.getUint32(at + 4, true);
    const chunk = buffer.slice(at + 8, at + 8 + length);
    if (type === 0x4e4f534a) json = JSON.parse(new TextDecoder().decode(chunk));
    else if (type === 0x004e4942) bin = chunk;
    at += 8 + length;
  }
  if (!json || !bin) throw new Error(`${url}: missing its JSON or BIN chunk`);
  return { json, bin };
}

// Accessor → Float32Array (or Uint32Array for indices), `count × components` values.
function readAccessor({ json, bin }, index, Out = Float32Array) {
  const accessor = json.accessors[index];
  const view = json.bufferViews[accessor.bufferView];
  const Component = componentArrays[accessor.componentType];
  const components = componentCounts[accessor.type];
  if (!Component || !components || accessor.sparse) throw new Error(`accessor ${index}: not read here`);
  const size = Component.BYTES_PER_ELEMENT;
  const stride = view.byteStride ?? size * components;
  const start = (view.byteOffset ?? 0) + (accessor.byteOffset ?? 0);
  const data = new DataView(bin);
  const out = new Out(accessor.count * components);
  const get = { 1: (o) => data.getUint8(o), 2: (o) => data.getUint16(o, true) }[size] ??
    (Component === Float32Array ? (o) => data.getFloat32(o, true) : (o) => data.getUint32(o, true));
  for (let i = 0; i < accessor.count; ++i)
    for (let c = 0; c < components; ++c) out[i * components + c] = get(start + i * stride + c * size);
  return out;
}

// Returns [{ positions, normals (or undefined), indices, joints: [Float32Array per set of 4],
//            weights: [same], bones: the bone texture's name (bones_skinK) }].
export async function readBonesMesh(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  const glb = parseGlb(await response.arrayBuffer(), url);
  const primitives = [];
  for (const mesh of glb.json.meshes ?? []) {
    for (const p of mesh.primitives) {
      if ((p.mode ?? 4) !== 4) throw new Error(`${url}: a primitive is not a triangle list (mode ${p.mode})`);
      const a = p.attributes;
      const positions = readAccessor(glb, a.POSITION);
      const count = positions.length / 3;
      const indices = p.indices !== undefined ? readAccessor(glb, p.indices, Uint32Array)
        : Uint32Array.from({ length: count }, (_, i) => i);
      const joints = [], weights = [];
      for (let set = 0; a[`_JOINTS_${set}`] !== undefined; ++set) {
        joints.push(readAccessor(glb, a[`_JOINTS_${set}`]));
        weights.push(readAccessor(glb, a[`_WEIGHTS_${set}`]));
      }
      if (!p.extras?.bones || joints.length === 0)
        throw new Error(`${url}: a primitive names no bone texture or has no _JOINTS_0`);
      primitives.push({
        positions, indices, joints, weights, bones: p.extras.bones,
        normals: a.NORMAL !== undefined ? readAccessor(glb, a.NORMAL) : undefined,
      });
    }
  }
  if (primitives.length === 0) throw new Error(`${url}: no primitives`);
  return primitives;
}
