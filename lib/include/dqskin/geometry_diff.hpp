// Comparing two glTF files by what they do, not what they store: both are deformed at the same times and
// their surfaces compared over every frame, so that an optimizer's or exporter's changes to tracks,
// quantization and vertex order are measured where they show (docs/DESIGN.md §7.3). A of the
// reference, B the candidate. The reports are dqskin/geometry_report.hpp's.
#pragma once

#include "dqskin/animation.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/image_diff.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dqskin {

struct GeometryDiffOptions {
  LoadOptions load;
  BlendMode mode = BlendMode::kDqs;  // both files are deformed the same way
  Backend backend = Backend::kAuto;
  unsigned threads = 0;              // CPU work (deforming, comparing): 0 for every core
  std::string clips = "all";         // A's clips to compare: all, a name or an index
  // Times: by default the union of both clips' key times and the midpoints between consecutive ones
  // (where resampling errors are largest); else the frames of A's clip under this FrameSpec (the fps grid
  // from 0 to A's last key, a range of it, A's key times), or its explicit times for every clip.
  std::optional<FrameSpec> frames;
  // idiff's thresholds, applied to the distance between corresponding surface points: in scene units, or
  // with `relative` as fractions of the clip's bounding-box diagonal (A's surface over every frame).
  // Percentages count vertex samples (each vertex of both sides at each frame).
  DiffThresholds thresholds;
  bool relative = false;
  // When set: for each failing clip, OUT/<clip>.error.png (its worst frame shaded by A's per-vertex error,
  // with a color bar and its scale in scene units), and OUT/worst_frames.png, a contact sheet of them.
  std::string out_dir;
  // When set: for every clip, the pictures of `dqskin diff --html` (dqskin/diff_page.hpp) under
  // PAGE/images: A's surface at the clip's worst frame shaded by its distance to B, and B's by its distance
  // to A, framed alike and on one scale, so that a toggle between them shows what moved.
  std::string page_dir;
  int image_size = 512;
  const std::atomic<bool>* cancel = nullptr;
};

// One frame's figures over both directions (A's vertices against B's surface and B's against A's).
struct FrameDiff {
  double time = 0;
  double max_error = 0, p99_error = 0, mean_error = 0;  // scene units
  double max_normal_degrees = 0;  // largest angle between corresponding normals (vertex or face normals:
                                  // GeometryDiffReport::smooth_normals_a says where which)
  std::string worst_joint;        // the joint the worst vertex mostly follows
};

// The worst error seen at vertices that mostly follow one joint (by its node's name, "node N" if unnamed).
struct JointDiff {
  std::string joint;
  double max_error = 0;
  double time = 0;
};

// Where the worst error of a clip is.
struct WorstVertex {
  char side = 'A';    // whose vertex: A's (measured against B's surface) or B's
  size_t vertex = 0;  // in the order of FrameView: instances, primitives, vertices
  double time = 0;
  std::string joint;
};

struct ClipGeometryDiff {
  std::string name;          // A's clip name ("#3" when unnamed; "rest pose" when neither file animates)
  std::string name_b;        // B's, when matched by index with another name; else equal to name
  DiffStatus status = DiffStatus::kPass;
  std::string reason;        // why it failed or warned, in words; empty on PASS
  double diagonal = 0;       // of A's bounding box over the clip's frames
  double max_error = 0;      // symmetric: the larger of the two directions
  double max_a_to_b = 0, max_b_to_a = 0;
  double mean_error = 0;     // over every sample of the clip
  double p99_error = 0;      // the largest 99th percentile of a frame
  double max_normal_degrees = 0;
  WorstVertex worst;
  uint64_t samples = 0, over_warn = 0, over_fail = 0;
  std::vector<FrameDiff> frames;
  std::vector<JointDiff> joints;  // worst first
  std::string heat_map;           // relative to out_dir, or empty
  std::string page_a, page_b;     // the page's pictures of A and B, relative to page_dir, or empty
};

// Something the files' animations say before anything is measured: a clip, channel or target in one file
// only, a changed duration or key count.
struct AnimationFinding {
  DiffStatus severity = DiffStatus::kPass;  // kFail for A's clip missing in B, kWarn for B's extra clip,
                                            // kPass for changes an optimizer makes on purpose (notes)
  std::string clip;
  std::string text;
};

struct GeometryDiffReport {
  std::string a, b;
  bool bake = false;             // two bake folders: one entry of `clips` per file, named by its path
  BlendMode mode = BlendMode::kDqs;
  DiffThresholds thresholds;
  bool relative = false;
  std::string deformer;          // describe(DeformPath) of what deformed
  bool identity = false;         // same vertices in the same order: compared vertex by vertex
  double correspondence_seconds = 0;
  // Where the correspondence was made: "rest" (the rest pose), "clip" (correspondence_clip at
  // correspondence_time: the rest pose of A or B is degenerate) or "bind" (the bind pose POSITION stores:
  // the rest pose is degenerate and so is the clip's, or no clip is compared).
  std::string correspondence_pose = "rest";
  std::string correspondence_clip;
  double correspondence_time = 0;
  // The share of each file's triangles that the rest pose distorts against the bind pose: an edge over
  // twice or under half its length there (against its primitive's median ratio), or the triangle turned
  // over. Over 5%: degenerate.
  double rest_distortion_a = 0, rest_distortion_b = 0;
  double rest_a_to_b = 0, rest_b_to_a = 0;  // largest distance to the other surface at that pose
  // How normals are compared: vertex normals where both files define one smooth normal at corresponding
  // points (A's vertices against B's surface, B's against A's), face normals elsewhere (flat shading,
  // split normals, a primitive without NORMAL): the triangles of each file compared so.
  size_t smooth_normals_a = 0, smooth_normals_b = 0;
  size_t face_normals_a = 0, face_normals_b = 0;
  size_t vertices_a = 0, vertices_b = 0;
  // Vertices used by no triangle of their primitive (unused ones, and those of points and lines): left out
  // of both directions and of the bounding box, since an optimizer drops them.
  size_t on_no_triangle_a = 0, on_no_triangle_b = 0;
  std::vector<AnimationFinding> findings;
  std::vector<ClipGeometryDiff> clips;
  std::string contact_sheet;     // relative to out_dir, or empty
  double wall_seconds = 0;

  // FAIL when a clip failed or a finding is a failure, else WARN likewise, else PASS.
  DiffStatus status() const;
};

// "the rest pose", "clip Walk, t = 0 s" or "the bind pose": where a report's correspondence was made.
std::string pose_text(const GeometryDiffReport& report);

// True when `path` is a folder `dqskin bake` wrote (it holds a manifest.json).
bool is_bake_folder(const std::string& path);

// Compares two bake folders: PLY, OBJ and glb frames paired by relative path and compared vertex by vertex
// (bake keeps the input's vertex order), EXR textures texel by texel (the distance between the first three
// channels: a VAT's positions). One report entry per file, `frames` holding its one figure; a file in one
// folder only, or with another vertex or texel count, or unreadable, fails. Throws InputError when neither
// folder holds such a file.
GeometryDiffReport diff_bakes(const std::string& a, const std::string& b, const GeometryDiffOptions& options);

// Loads and compares two glTF files. Throws InputError naming the file for a file that does not load,
// and naming the problem when the files cannot be compared (no clip in common, no triangles, surfaces
// that do not overlap at rest); NoGpuContext when the backend needs a context that cannot be made;
// JobCancelled; OutputError for images that cannot be written.
GeometryDiffReport diff_geometry(const std::string& a, const std::string& b, const GeometryDiffOptions& options);

}  // namespace dqskin
