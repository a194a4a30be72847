// One frame as a static glTF 2.0 binary (glb_output.hpp): the scene's nodes with their transforms at the
// frame's time, one new mesh per instance with the deformed vertices in its node's local space, and the
// fixed parts (glb_appearance.cpp) shared by every frame. Container layout: glTF 2.0 §4.4 "Binary glTF".
#include "glb_output.hpp"
#include "dqskin/triangles.hpp"

#include "dqskin/error.hpp"
#include "glb_appearance.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace dqskin {

using glb::json;

struct GlbWriter::Impl {
  const Asset* asset = nullptr;
  std::vector<MeshInstance> instances;
  glb::Appearance fixed;
  std::vector<int> kept;         // the source nodes written, ascending: node i of the output is kept[i]
  std::vector<int> new_index;    // per source node: its output index, or -1
  std::vector<int> roots;        // output indices of the scene's roots, in scene order
  std::vector<int> instance_of;  // per source node: the instance it draws, or -1
};

namespace {

using DVec3 = Vec3<double>;
using DVec4 = glm::vec<4, double, glm::defaultp>;

// Where an instance's vertices go: its node's local space (to_local = inverse(world)) or, detached, world
// space under an identity root node.
struct Space {
  bool attached = false;
  Mat4<double> to_local{1.0};
  Mat3<double> normals{1.0};   // inverse-transpose of to_local's 3×3: transpose(world 3×3)
  Mat3<double> tangents{1.0};  // to_local's 3×3
  bool flip_winding = false;
};

// Whether the node can carry the mesh: inverse(world) must exist and keep float precision. The node's
// scale costs nothing in floating point, however small; what loses digits is columns that are nearly
// dependent. |det| / (|c0| |c1| |c2|) (Hadamard's ratio: 1 for orthogonal columns, 0 for a singular matrix
// such as a zero scale) bounds the condition number of the column-normalised matrix by 3√3 / ratio, and
// the round trip world · float(inverse(world) · p) errs by at most float's 6e-8 times that, relative to
// |p − node origin|: 3e-3 at the limit of 1e-4. Below it the mesh is detached.
Space space_of(const Mat4<double>& world, bool skinned) {
  const Mat3<double> a(world);
  const double det = glm::determinant(a);
  const double columns = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  Space s;
  s.attached = columns > 0 && std::isfinite(columns) && std::abs(det) > 1e-4 * columns;
  if (!s.attached) return s;
  s.to_local = glm::inverse(world);
  s.normals = glm::transpose(a);
  s.tangents = glm::inverse(a);
  // §3.7.4: the determinant's sign of the node's global transform chooses the front face. A skinned mesh
  // ignored it (§3.7.3.1); now that the node carries the mesh, a mirroring node would turn its faces.
  s.flip_winding = skinned && det < 0;
  return s;
}

using glb::unit_or;

// The rest normal or tangent of vertex v (in the mesh's own space), else `fallback`.
template <typename V>
glm::vec3 rest_or(const std::vector<V>& rest, size_t v, const glm::vec3& fallback) {
  return v < rest.size() ? unit_or(DVec3(glm::vec3(rest[v])), fallback) : fallback;
}

struct Vertices {
  std::vector<float> positions, normals, tangents;
};

// One primitive's vertices in `space`, or nothing when a position does not fit in float there.
std::optional<Vertices> in_space(const Primitive& prim, const PrimitiveView& view, const Space& space) {
  constexpr double kFloatMax = double(std::numeric_limits<float>::max());
  Vertices out;
  out.positions.reserve(view.vertices * 3);
  for (size_t v = 0; v < view.vertices; ++v) {
    const DVec3 world(view.positions[3 * v], view.positions[3 * v + 1], view.positions[3 * v + 2]);
    if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z))
      throw std::invalid_argument("GlbWriter: vertex " + std::to_string(v) + " has a non-finite position");
    const DVec3 p = DVec3(space.to_local * DVec4(world, 1.0));
    for (int c = 0; c < 3; ++c) {
      if (!(std::abs(p[c]) <= kFloatMax)) return std::nullopt;
      out.positions.push_back(float(p[c]));
    }
  }
  // NORMAL only where the source has it: §3.7.2.1 asks viewers for flat normals otherwise.
  if (!prim.normals_generated && !view.normals.empty()) {
    for (size_t v = 0; v < view.vertices; ++v) {
      const DVec3 n(view.normals[3 * v], view.normals[3 * v + 1], view.normals[3 * v + 2]);
      const glm::vec3 u = unit_or(space.normals * n, rest_or(prim.normals, v, {0, 0, 1}));
      out.normals.insert(out.normals.end(), {u.x, u.y, u.z});
    }
  }
  // TANGENT without NORMAL must be ignored (§3.7.2.1), so it is not written.
  if (!out.normals.empty() && !view.tangents.empty()) {
    for (size_t v = 0; v < view.vertices; ++v) {
      const DVec3 t(view.tangents[4 * v], view.tangents[4 * v + 1], view.tangents[4 * v + 2]);
      const glm::vec3 u = unit_or(space.tangents * t, rest_or(prim.tangents, v, {1, 0, 0}));
      out.tangents.insert(out.tangents.end(), {u.x, u.y, u.z, view.tangents[4 * v + 3] < 0 ? -1.0f : 1.0f});
    }
  }
  return out;
}

// The mesh of one instance (its primitives' vertices in `space`), or null when they do not fit there.
json instance_mesh(const Asset& asset, const glb::Appearance& fixed, const MeshInstance& inst,
                   std::span<const PrimitiveView> views, const Space& space, glb::BinWriter& bin) {
  const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
  std::vector<Vertices> vertices;
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    std::optional<Vertices> v = in_space(mesh.primitives[p], views[p], space);
    if (!v) return nullptr;
    vertices.push_back(std::move(*v));
  }
  json primitives = json::array();
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const Primitive& prim = mesh.primitives[p];
    const glb::FixedPrimitive& f = fixed.meshes[size_t(inst.mesh)][p];
    const Vertices& v = vertices[p];
    json out = {{"attributes", f.attributes}};
    out["attributes"]["POSITION"] = bin.positions(v.positions);
    if (!v.normals.empty()) out["attributes"]["NORMAL"] = bin.floats(v.normals, prim.vertex_count(), "VEC3");
    if (!v.tangents.empty()) out["attributes"]["TANGENT"] = bin.floats(v.tangents, prim.vertex_count(), "VEC4");

    int mode = int(prim.mode);
    const bool triangles = mode >= int(PrimitiveMode::kTriangles);
    if (space.flip_winding && triangles) {
      std::vector<uint32_t> list = triangle_list(prim);
      for (size_t t = 0; t + 2 < list.size(); t += 3) std::swap(list[t + 1], list[t + 2]);
      out["indices"] = bin.indices(list);
      mode = int(PrimitiveMode::kTriangles);
    } else if (f.indices >= 0) {
      out["indices"] = f.indices;
    }
    if (mode != int(PrimitiveMode::kTriangles)) out["mode"] = mode;  // the default (§5.24)
    if (f.material >= 0) out["material"] = f.material;
    if (!f.extras.is_null()) out["extras"] = f.extras;
    if (!f.extensions.is_null()) out["extensions"] = f.extensions;
    primitives.push_back(std::move(out));
  }
  json result = {{"primitives", std::move(primitives)}};
  if (!mesh.name.empty()) result["name"] = mesh.name;
  if (!fixed.mesh_extras[size_t(inst.mesh)].is_null()) result["extras"] = fixed.mesh_extras[size_t(inst.mesh)];
  return result;
}

// A node's transform at this frame, default values omitted (§5.25: matrix or TRS, never both).
void put_transform(const LocalTransform& t, json& node) {
  if (t.has_matrix) {
    if (t.matrix == Mat4<double>(1.0)) return;
    json m = json::array();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m.push_back(t.matrix[c][r]);  // column-major
    node["matrix"] = std::move(m);
    return;
  }
  if (t.translation != DVec3(0.0)) node["translation"] = {t.translation.x, t.translation.y, t.translation.z};
  if (t.rotation != Quat<double>(1, 0, 0, 0)) node["rotation"] = {t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w};
  if (t.scale != DVec3(1.0)) node["scale"] = {t.scale.x, t.scale.y, t.scale.z};
}

// Every node's local transform at `time`: rest, then the clip's channels, as sample_pose sets them, so
// that the world matrices a viewer computes are the ones the vertices were placed with.
std::vector<LocalTransform> local_transforms(const Asset& asset, const Clip* clip, double time) {
  std::vector<LocalTransform> local(asset.nodes.size());
  for (size_t i = 0; i < local.size(); ++i) local[i] = asset.nodes[i].local;
  if (!clip) return local;
  for (const Channel& ch : clip->channels) {
    if (ch.path == TargetPath::kWeights) continue;
    const std::vector<double> v = sample_channel(ch, time);
    LocalTransform& t = local[size_t(ch.node)];
    if (ch.path == TargetPath::kTranslation) t.translation = {v[0], v[1], v[2]};
    if (ch.path == TargetPath::kRotation) t.rotation = Quat<double>(v[3], v[0], v[1], v[2]);
    if (ch.path == TargetPath::kScale) t.scale = {v[0], v[1], v[2]};
  }
  return local;
}

// A scene root's transform with a clip's ground motion `g` taken out, as sample_pose took it out of the world
// matrices (docs/DESIGN.md §3.11): M⁻¹ · local, with M⁻¹ rigid, so a TRS stays a TRS.
LocalTransform without_ground_motion(LocalTransform t, const GroundMotion& g) {
  const Mat4<double> to_place = ground_matrix_inverse(g);
  if (t.has_matrix) {
    t.matrix = to_place * t.matrix;
    return t;
  }
  t.translation = DVec3(to_place * glm::dvec4(t.translation, 1.0));
  t.rotation = glm::angleAxis(-g.yaw, DVec3(0, 1, 0)) * t.rotation;
  return t;
}

}  // namespace

GlbImages parse_glb_images(const std::string& name) {
  for (GlbImages mode : {GlbImages::kEmbed, GlbImages::kShared, GlbImages::kNone})
    if (name == to_string(mode)) return mode;
  throw InputError("--glb-images '" + name + "' is not one of embed, shared, none");
}

const char* to_string(GlbImages images) {
  switch (images) {
    case GlbImages::kEmbed: return "embed";
    case GlbImages::kShared: return "shared";
    case GlbImages::kNone: break;
  }
  return "none";
}

GlbWriter::GlbWriter(const Asset& asset, std::vector<MeshInstance> instances, int scene, GlbImages images) {
  auto w = std::make_unique<Impl>();
  w->asset = &asset;
  w->instances = std::move(instances);
  if (scene >= int(asset.scenes.size())) throw std::invalid_argument("GlbWriter: scene does not exist");
  w->fixed = glb::read_appearance(asset, w->instances, scene, images);

  // The nodes the scene reaches (§3.5.3); with no scene, every tree.
  std::vector<int> roots;
  if (scene >= 0) roots = asset.scenes[size_t(scene)].roots;
  for (size_t i = 0; scene < 0 && i < asset.nodes.size(); ++i)
    if (asset.nodes[i].parent < 0) roots.push_back(int(i));
  std::vector<char> reached(asset.nodes.size(), 0);
  for (std::vector<int> stack = roots; !stack.empty();) {
    const int n = stack.back();
    stack.pop_back();
    reached[size_t(n)] = 1;
    stack.insert(stack.end(), asset.nodes[size_t(n)].children.begin(), asset.nodes[size_t(n)].children.end());
  }
  w->new_index.assign(asset.nodes.size(), -1);
  for (size_t i = 0; i < asset.nodes.size(); ++i)
    if (reached[i]) w->new_index[i] = int(w->kept.size()), w->kept.push_back(int(i));
  for (int r : roots) w->roots.push_back(w->new_index[size_t(r)]);

  w->instance_of.assign(asset.nodes.size(), -1);
  for (size_t k = 0; k < w->instances.size(); ++k) {
    const int node = w->instances[k].node;
    if (node < 0 || size_t(node) >= asset.nodes.size() || !reached[size_t(node)] || w->instance_of[size_t(node)] >= 0)
      throw std::invalid_argument("GlbWriter: instance " + std::to_string(k) + " is not a node of the scene, or a second one");
    w->instance_of[size_t(node)] = int(k);
  }
  impl_ = std::move(w);
}

GlbWriter::~GlbWriter() = default;
GlbWriter::GlbWriter(GlbWriter&&) noexcept = default;
GlbWriter& GlbWriter::operator=(GlbWriter&&) noexcept = default;

const std::vector<GlbImageFile>& GlbWriter::image_files() const { return impl_->fixed.image_files; }

std::string GlbWriter::encode(const FrameView& frame, const Clip* clip, double time) const {
  const Impl& w = *impl_;
  const Asset& asset = *w.asset;
  size_t expected = 0;
  for (const MeshInstance& inst : w.instances) expected += asset.meshes[size_t(inst.mesh)].primitives.size();
  if (frame.primitives.size() != expected)
    throw std::invalid_argument("GlbWriter: the frame has " + std::to_string(frame.primitives.size()) +
                                " primitives, the instances " + std::to_string(expected));

  const Pose pose = sample_pose(asset, clip, time);
  std::vector<LocalTransform> local = local_transforms(asset, clip, time);
  if (pose.removed)  // an in-place clip: the viewer's world matrices must be the in-place ones too
    for (size_t n = 0; n < local.size(); ++n)
      if (asset.nodes[n].parent < 0) local[n] = without_ground_motion(local[n], *pose.removed);
  json doc = w.fixed.doc;
  glb::BinWriter bin = w.fixed.bin;
  json meshes = json::array();
  std::vector<bool> attached(w.instances.size(), false);
  json detached = json::array();
  json scene = w.fixed.scene_fields;
  scene["nodes"] = w.roots;

  size_t first = 0;
  for (size_t k = 0; k < w.instances.size(); ++k) {
    const MeshInstance& inst = w.instances[k];
    const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
    const std::span<const PrimitiveView> views = std::span(frame.primitives).subspan(first, mesh.primitives.size());
    first += mesh.primitives.size();
    for (size_t p = 0; p < views.size(); ++p) {
      const PrimitiveView& v = views[p];
      const size_t n = mesh.primitives[p].vertex_count();
      if (v.vertices != n || v.positions.size() != 3 * n || (!v.normals.empty() && v.normals.size() != 3 * n) ||
          (!v.tangents.empty() && v.tangents.size() != 4 * n))
        throw std::invalid_argument("GlbWriter: instance " + std::to_string(k) + " primitive " + std::to_string(p) +
                                    " does not match the mesh's " + std::to_string(n) + " vertices");
    }
    const Space space = space_of(pose.world[size_t(inst.node)], inst.skin >= 0);
    json m = space.attached ? instance_mesh(asset, w.fixed, inst, views, space, bin) : json();
    attached[k] = !m.is_null();
    if (!attached[k]) {  // singular world matrix: the world-space vertices under an identity root
      m = instance_mesh(asset, w.fixed, inst, views, Space{}, bin);
      const std::string& name = asset.nodes[size_t(inst.node)].name;
      scene["nodes"].push_back(w.kept.size() + detached.size());
      detached.push_back({{"name", (name.empty() ? "node " + std::to_string(inst.node) : name) + " (deformed)"},
                          {"mesh", k}});
    }
    meshes.push_back(std::move(m));
  }

  json nodes = json::array();
  for (const int n : w.kept) {
    json node = w.fixed.nodes[size_t(n)].fields;
    put_transform(local[size_t(n)], node);
    for (int c : asset.nodes[size_t(n)].children) node["children"].push_back(w.new_index[size_t(c)]);
    if (const int k = w.instance_of[size_t(n)]; k >= 0 && attached[size_t(k)]) node["mesh"] = k;
    nodes.push_back(std::move(node));
  }
  for (json& node : detached) nodes.push_back(std::move(node));

  doc["meshes"] = std::move(meshes);
  doc["nodes"] = std::move(nodes);
  if (scene["nodes"].empty()) scene.erase("nodes");
  doc["scenes"] = json::array({scene});
  doc["scene"] = 0;
  return glb::finish_glb(std::move(doc), std::move(bin), w.fixed.source_extensions_required);
}

}  // namespace dqskin
