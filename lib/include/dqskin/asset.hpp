// The Asset: what dqskin keeps of a glTF 2.0 file (docs/DESIGN.md §2.1). Plain data, no tinygltf
// types; every index in it has been checked against the array it indexes, every float is finite.
// Appearance (materials, textures, cameras) with a broken reference or value loads with a warning and
// that part dropped: it does not change the deformation.
#pragma once

#include "dqskin/dual_quat.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace dqskin {

// glTF primitive.mode values.
enum class PrimitiveMode : int { kPoints = 0, kLines, kLineLoop, kLineStrip, kTriangles, kTriangleStrip, kTriangleFan };

// Influence sets (JOINTS_n/WEIGHTS_n pairs, glTF 2.0 §3.7.3.3) read at most: 8 sets are 32 influences per
// vertex, four times what any real-time runtime takes and past the 20 that real exports carry. A bound
// keeps a few bytes of JSON (JOINTS_0 … JOINTS_999 naming one accessor) from decoding to gigabytes; the
// loader refuses more sets and `lint` reads no more either.
inline constexpr int kMaxInfluenceSets = 8;
inline constexpr int kMaxInfluences = 4 * kMaxInfluenceSets;

// Per-vertex offsets of one morph target; an attribute the target does not move is empty.
struct MorphTarget {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> tangents;
};

// One mesh primitive with its attributes decoded to float, in accessor order.
struct Primitive {
  PrimitiveMode mode = PrimitiveMode::kTriangles;
  int material = -1;                 // index into the file's materials, or -1
  int position_accessor = -1;        // the file's POSITION accessor (primitives may share one)
  // Every attribute and morph target attribute with the file's accessor for it ("NORMAL", "1/POSITION" for
  // target 1), in name order: primitives whose lists are equal share their vertices (vertex_sharing.hpp).
  // Empty for primitives that are not read from a file.
  std::vector<std::pair<std::string, int>> vertex_accessors;
  std::vector<glm::vec3> positions;  // POSITION; its size is the vertex count
  std::vector<glm::vec3> normals;    // NORMAL, or generated (see normals_generated); empty for non-triangles without
  std::vector<glm::vec4> tangents;   // TANGENT (xyz, w = handedness ±1), or empty
  std::vector<glm::vec2> uv0;        // TEXCOORD_0, or empty
  std::vector<glm::vec2> uv1;        // TEXCOORD_1, or empty (a material's texture may read either set)
  std::vector<glm::vec4> colors;     // COLOR_0 as linear RGBA (alpha 1 when stored as RGB), or empty
  std::vector<uint32_t> indices;     // empty when not indexed
  bool normals_generated = false;    // NORMAL was absent: smooth normals were computed (see load.hpp)

  // Skin influences, `influences` per vertex (0, or 4 per JOINTS_n/WEIGHTS_n set, at most kMaxInfluences),
  // vertex-major. Weights are as stored (normalized integers decoded), not renormalised, unless
  // LoadOptions::max_influences cut them (then the kept ones sum to 1).
  int influences = 0;
  std::vector<uint16_t> joints;
  std::vector<float> weights;

  std::vector<MorphTarget> targets;

  size_t vertex_count() const { return positions.size(); }
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
  std::vector<float> weights;  // default morph weights, one per target (zeros when the file has none)
};

// A node's local transform as glTF stores it: a matrix, or translation/rotation/scale.
struct LocalTransform {
  bool has_matrix = false;
  Mat4<double> matrix{1.0};
  Vec3<double> translation{0.0};
  Quat<double> rotation{1.0, 0.0, 0.0, 0.0};
  Vec3<double> scale{1.0};

  Mat4<double> to_matrix() const;
};

struct Node {
  std::string name;
  int parent = -1;
  std::vector<int> children;
  LocalTransform local;
  int mesh = -1;
  int skin = -1;
  int camera = -1;             // index into Asset::cameras, or -1
  std::vector<float> weights;  // the node's morph weights, overriding the mesh's, or empty
};

struct Skin {
  std::string name;
  std::vector<int> joints;                // node indices
  std::vector<Mat4<double>> inverse_bind; // one per joint; identity when the file has none
  int skeleton = -1;                      // node index, or -1
};

enum class TargetPath { kTranslation, kRotation, kScale, kWeights };
// The path as glTF spells it ("translation", "rotation", "scale", "weights"), for messages.
const char* target_path_name(TargetPath path);
enum class Interpolation { kStep, kLinear, kCubicSpline };

// One animation channel with its sampler's data. times are strictly increasing. values holds, per key,
// `components` floats (3 for translation/scale, 4 for rotation as x, y, z, w, the morph target count for
// weights), and for CUBICSPLINE three such groups per key: in-tangent, value, out-tangent.
struct Channel {
  int node = -1;
  TargetPath path = TargetPath::kTranslation;
  Interpolation interpolation = Interpolation::kLinear;
  std::vector<float> times;
  std::vector<float> values;
  int components = 0;
};

struct Clip {
  std::string name;
  std::vector<Channel> channels;
  double first_key = 0;  // smallest key time over all channels
  double last_key = 0;   // largest key time: the clip's duration, as glTF time 0 is the clip's start
  // Not from the file: a node whose ground motion sample_pose takes out of every node's world matrix (a bake
  // with --root-motion in-place sets it, docs/DESIGN.md §3.11); -1: none.
  int in_place_root = -1;
};

// KHR_texture_transform on a textureInfo: the texture is read at uv' = T · R · S · uv, T translating by
// `offset`, S scaling by `scale`, R turning the UVs `rotation` radians counter-clockwise as seen on the
// image (u right, v down), so that the image appears turned clockwise on the surface, as the extension
// says. The defaults are the identity.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0;
  glm::vec2 scale{1.0f};

  // T · R · S as a 3x3 matrix (glm, column-major) for homogeneous UVs (u, v, 1):
  //   u' =  cos(r) sx u + sin(r) sy v + offset.x
  //   v' = -sin(r) sx u + cos(r) sy v + offset.y
  // R is the turn of three.js's Matrix3.setUvTransform and the one the extension's example JSON needs
  // (offset (0, 1), rotation 90°, scale 0.5 reads the lower-left quadrant); the GLSL listing in the
  // extension's README, read as column-major GLSL, is its transpose, the opposite turn (KhronosGroup/glTF
  // issue #1563, open).
  glm::mat3 matrix() const;
};

// glTF textureInfo (§5.30): a texture and the TEXCOORD_n set it is read with.
struct TextureRef {
  int texture = -1;  // index into Asset::textures, or -1 for none
  int texcoord = 0;  // n of TEXCOORD_n: the textureInfo's, or its KHR_texture_transform's texCoord, which overrides it
  TextureTransform transform;  // KHR_texture_transform, or the identity
};

enum class AlphaMode { kOpaque, kMask, kBlend };

// What the mesh writers (OBJ's .mtl) and the renderer need of a material; the glb writer copies the
// file's own.
struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};  // pbrMetallicRoughness.baseColorFactor, linear RGBA (default 1, 1, 1, 1)
  TextureRef base_color_texture;  // pbrMetallicRoughness.baseColorTexture: sRGB color, linear alpha
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;   // kMask: fragments with a lower alpha are not drawn
};

// A sampler's filters and wrap modes as glTF stores them (OpenGL enum values, §5.26). A filter of 0 is
// one the file leaves to the viewer.
struct Sampler {
  int mag_filter = 0, min_filter = 0;
  int wrap_s = 10497, wrap_t = 10497;  // REPEAT
};

struct Texture {
  int image = -1;  // index into Asset::images: EXT_texture_webp's image, else the core source; -1 when none is drawn (only a KTX2 image)
  Sampler sampler;
};

// An image as the file stores it (PNG or JPEG bytes, §3.8.3), not decoded: only the renderer needs its
// pixels, and decoding belongs to the image library there.
struct EncodedImage {
  std::string name;
  std::string mime_type;  // as the file says, or empty (an external file or data URI may not say)
  std::string uri;        // the external file's URI, for messages; empty when embedded
  std::vector<uint8_t> bytes;  // empty when the external file could not be read
};

// A glTF camera (§3.10). Angles in radians, distances in the scene's units.
struct SceneCamera {
  std::string name;
  bool orthographic = false;
  double yfov = 0;          // perspective: vertical field of view
  double aspect_ratio = 0;  // perspective: width / height, or 0 for the viewport's
  double xmag = 0, ymag = 0;  // orthographic: half the view's width and height
  double znear = 0;
  double zfar = 0;          // 0: infinite (perspective only)
  std::string problem;      // why the file's values cannot be used (also in Asset::warnings), or empty
};

struct Scene {
  std::string name;
  std::vector<int> roots;
};

// What the .glb writer copies from the file besides the Asset (lib/asset/source_document.hpp: the checked
// JSON, TEXCOORD_n and COLOR_n); opaque here, so that no JSON type appears in the Asset.
struct SourceDocument;

struct Asset {
  std::string path;  // as given to the loader, for messages
  std::vector<Node> nodes;
  std::vector<Mesh> meshes;
  std::vector<Skin> skins;
  std::vector<Clip> clips;
  std::vector<Scene> scenes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<EncodedImage> images;
  std::vector<SceneCamera> cameras;
  int default_scene = -1;
  std::vector<std::string> warnings;  // things that are allowed but worth telling the user
  // What the file does that glTF defines and dqskin follows as it says, worth telling only when asked (a
  // skinned mesh node's transform, which glTF ignores): `info` and `lint` print them, the other commands
  // with --verbose. One line each, once per file.
  std::vector<std::string> notices;
  // Why the file, though it is read, cannot be deformed (two different channels for one node and path,
  // say): one line each, naming the objects and the rule. Empty for every file the deforming commands
  // accept. Only loads with LoadOptions::refuse_undeformable off can see it non-empty (info, lint).
  std::vector<std::string> cannot_deform;
  std::shared_ptr<const SourceDocument> source;  // with LoadOptions::keep_source, else null
};

}  // namespace dqskin
