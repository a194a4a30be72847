#include "motion_files.hpp"

#include "../base/output_journal.hpp"
#include "../texture/texel_image.hpp"

#include "dqskin/animation.hpp"
#include "dqskin/dual_quat.hpp"
#include "dqskin/error.hpp"

#include <nlohmann/json.hpp>

namespace dqskin::bake_detail {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written, for people reading the files

// Texels per socket and frame: the three rows of the affine 3x4 world matrix, the dual quaternion's real
// and dual parts.
constexpr size_t kTexelsPerSocket = 5;

std::string dump(const Json& j) { return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

Json timing(const ClipPlan& clip) {
  Json doc;
  doc["animation"] = clip.name;
  doc["frame_count"] = clip.times.size();
  doc["fps"] = clip.fps > 0 ? Json(clip.fps) : Json(nullptr);
  doc["frame_numbers"] = clip.numbers;
  doc["frame_times"] = clip.times;
  return doc;
}

Committed commit_text(const std::string& path, const std::string& text, const CommitOptions& commit) {
  AtomicFile file(path, false);  // the bake syncs the file system once, before the manifest
  file.write(text);
  return file.commit(commit);
}

// sockets.json and sockets.exr from every frame's world matrices of the sockets.
std::vector<std::pair<std::string, Committed>> write_sockets(const InputPlan& input, const ClipPlan& clip,
                                                             const std::vector<std::vector<Mat4<double>>>& world,
                                                             const MotionNodes& nodes, const BakeOptions& options,
                                                             const CommitOptions& commit) {
  const Asset& asset = *input.asset;
  const size_t frames = clip.times.size(), count = nodes.sockets.size();
  texture::TexelImage image(texture::TexelType::kFloat32, kTexelsPerSocket * count, frames, 4);
  Json sockets = Json::array();
  for (size_t s = 0; s < count; ++s) {
    Json matrices = Json::array(), dual_quats = Json::array();
    for (size_t f = 0; f < frames; ++f) {
      const Mat4<double>& m = world[f][s];
      const DualQuat<double> q = split_joint_matrix(m).rigid;
      Json column_major = Json::array();
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) column_major.push_back(m[c][r]);
      matrices.push_back(std::move(column_major));
      dual_quats.push_back({q.real.x, q.real.y, q.real.z, q.real.w, q.dual.x, q.dual.y, q.dual.z, q.dual.w});
      const size_t x = kTexelsPerSocket * s;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) image.set(x + size_t(r), f, c, float(m[c][r]));
      const double parts[2][4] = {{q.real.x, q.real.y, q.real.z, q.real.w}, {q.dual.x, q.dual.y, q.dual.z, q.dual.w}};
      for (int p = 0; p < 2; ++p)
        for (int c = 0; c < 4; ++c) image.set(x + 3 + size_t(p), f, c, float(parts[p][c]));
    }
    const int node = nodes.sockets[s];
    sockets.push_back({{"name", asset.nodes[size_t(node)].name},
                       {"node", node},
                       {"matrices", std::move(matrices)},
                       {"dual_quaternions", std::move(dual_quats)}});
  }
  if (const std::string at = image.first_non_finite(); !at.empty())
    throw InputError("clip " + clip.name + ": a socket's world transform is not finite at texel " + at);

  Json doc;
  doc["format"] = "dqskin sockets";
  doc["version"] = 1;
  doc.update(timing(clip));
  doc["in_place"] = nodes.root >= 0 && clip.clip;
  doc["matrix"] = "the node's world matrix at the frame, 16 numbers column-major (glTF's order), in the space of the "
                  "bake's frames (in place with --root-motion in-place)";
  doc["dual_quaternion"] = "real (x, y, z, w), dual (x, y, z, w), w scalar: the unit dual quaternion of the world "
                           "matrix's rigid part (its nearest rotation, then its translation); equal to the matrix "
                           "when the matrix has no scale";
  doc["sockets"] = std::move(sockets);
  doc["texture"] = {{"file", kSocketsTexture},
                    {"width", image.width()},
                    {"height", frames},
                    {"channels", "RGBA"},
                    {"type", "float32"},
                    {"texels_per_socket", kTexelsPerSocket},
                    {"texel", "component k of socket s at frame f is at (5 * s + k, f), row 0 the first of the file: "
                              "k = 0, 1, 2 row k of the world matrix's affine 3x4 part (x, y, z, w = m[k][0], m[k][1], "
                              "m[k][2], translation[k]); k = 3 the dual quaternion's real part, k = 4 its dual part "
                              "(x, y, z, w; w scalar)"}};

  const std::string folder = options.plan.out_dir + "/" + clip.folder + "/";
  AtomicFile exr(folder + kSocketsTexture, false);
  {
    texture::TexelFileWriter writer(exr, texture::TexelType::kFloat32, image.width(), frames, 4,
                                    texture::exr_compression(options.textures.exr_compression));
    writer.write(image);
    writer.close();
  }
  AtomicFile json(folder + kSocketsJson, false);
  json.write(dump(doc));
  if (commit.overwrite == Overwrite::kRefuseDifferent)
    for (const AtomicFile* f : {&exr, &json})
      if (f->conflicts()) throw OutputError(f->path() + ": exists with different contents; not overwritten");
  return {{clip.folder + "/" + kSocketsJson, json.commit(commit)}, {clip.folder + "/" + kSocketsTexture, exr.commit(commit)}};
}

std::string root_motion_text(const Asset& asset, const ClipPlan& clip, const std::vector<GroundMotion>& track, int root) {
  Json doc;
  doc["format"] = "dqskin root motion";
  doc["version"] = 1;
  doc.update(timing(clip));
  doc["root"] = {{"node", root}, {"name", asset.nodes[size_t(root)].name}};
  doc["definition"] =
      "original = M(t) * in_place for every world matrix and every vertex of a frame, M(t) = T(x, 0, z) * Ry(yaw): "
      "x and z the root's world origin on the ground plane (y up), yaw the twist about +Y of the root's world "
      "rotation, in radians in [-pi, pi] (docs/DESIGN.md §3.11). Absolute, not relative to the first frame: "
      "the motion from frame a to frame b is M(a)^-1 * M(b)";
  Json x = Json::array(), z = Json::array(), yaw = Json::array();
  for (const GroundMotion& g : track) x.push_back(g.x), z.push_back(g.z), yaw.push_back(g.yaw);
  doc["x"] = std::move(x);
  doc["z"] = std::move(z);
  doc["yaw"] = std::move(yaw);
  return dump(doc);
}

}  // namespace

std::vector<std::string> planned_motion_files(const ClipPlan& clip, const MotionNodes& nodes) {
  std::vector<std::string> files;
  if (!clip.clip_mine) return files;
  if (!nodes.sockets.empty()) {
    files.push_back(clip.folder + "/" + kSocketsJson);
    files.push_back(clip.folder + "/" + kSocketsTexture);
  }
  if (nodes.root >= 0 && clip.clip) files.push_back(clip.folder + "/" + kRootMotionJson);
  return files;
}

std::vector<std::pair<std::string, Committed>> write_motion_files(const InputPlan& input, const ClipPlan& clip,
                                                                  const MotionNodes& nodes, const BakeOptions& options,
                                                                  const CommitOptions& commit) {
  std::vector<std::pair<std::string, Committed>> files;
  if (planned_motion_files(clip, nodes).empty()) return files;
  const Asset& asset = *input.asset;
  // The clip's folder, which no other output may have made (--combine-clips writes elsewhere), under the
  // input's journal so that a failure takes it back.
  if (commit.journal) commit.journal->make_folders(options.plan.out_dir + "/" + clip.folder);
  std::vector<std::vector<Mat4<double>>> world(clip.times.size());
  std::vector<GroundMotion> track(clip.times.size());
  for (size_t f = 0; f < clip.times.size(); ++f) {
    const Pose pose = sample_pose(asset, clip.clip, clip.times[f]);  // the pose every deformer sampled
    for (int n : nodes.sockets) world[f].push_back(pose.world[size_t(n)]);
    if (pose.removed) track[f] = *pose.removed;
  }
  if (!nodes.sockets.empty())
    for (auto& file : write_sockets(input, clip, world, nodes, options, commit)) files.push_back(std::move(file));
  if (nodes.root >= 0 && clip.clip) {
    const std::string name = clip.folder + "/" + kRootMotionJson;
    files.emplace_back(name, commit_text(options.plan.out_dir + "/" + name,
                                         root_motion_text(asset, clip, track, nodes.root), commit));
  }
  return files;
}

}  // namespace dqskin::bake_detail
