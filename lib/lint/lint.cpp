// `dqskin lint` over one file: read its raw skin data, run every group of checks, and turn their tallies
// into findings in the catalogue's order (lint_checks()).
#include "dqskin/lint.hpp"

#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "lint_checks.hpp"

#include <new>
#include <set>

namespace dqskin {

const char* to_string(LintSeverity severity) {
  switch (severity) {
    case LintSeverity::kInfo: return "info";
    case LintSeverity::kWarning: return "warning";
    case LintSeverity::kError: return "error";
  }
  return "error";
}

const std::vector<LintCheckInfo>& lint_checks() {
  using S = LintSeverity;
  static const std::vector<LintCheckInfo> checks = {
      {"cannot-deform", S::kError,
       "the file is read, but bake, render, report and diff refuse to deform it (the message says why)", false},
      {"weight-sum", S::kError,
       "a vertex's weights (over every WEIGHTS_n) sum away from 1 beyond what the component type allows", true},
      {"zero-weight-vertex", S::kError, "a vertex has no weight on any joint (--fix binds it to the nearest joint)",
       true},
      {"negative-weight", S::kError, "a weight is negative", true},
      {"duplicate-joint", S::kError, "the same joint twice in one vertex, both with weight", true},
      {"joint-out-of-range", S::kError, "a joint index beyond the joints of every skin that draws the mesh", true},
      {"joint-beyond-smaller-skin", S::kWarning,
       "a joint index that fits the larger of the skins that draw the mesh but not a smaller one (--fix keeps "
       "it: the larger skin needs it)",
       false},
      {"over-8-influences", S::kWarning,
       "more than 8 (and --max-influences) joints with weight on one vertex: Babylon.js reads 8 (JOINTS_0/1), "
       "three.js 4 (JOINTS_0); they drop the rest (dqskin reads up to 32)",
       true},
      {"too-many-influences", S::kWarning,
       "more than --max-influences (and at most 8) joints with weight on one vertex: three.js reads only 4 "
       "(JOINTS_0) and drops the rest",
       true},
      {"unused-joint", S::kInfo, "a joint of the skin with weight on no vertex", false},
      {"no-common-root", S::kError, "the skin's joints hang under different root nodes", false},
      {"skeleton-not-root", S::kError,
       "the skin's skeleton node is not an ancestor of every joint (--fix removes the property)", true},
      {"joint-not-in-scene", S::kError,
       "a joint is not in a scene that draws its skin (runtimes pose only the scene's nodes)", false},
      {"ibm-not-affine", S::kError, "an inverse bind matrix's fourth row is not (0, 0, 0, 1)", false},
      {"ibm-not-invertible", S::kError, "an inverse bind matrix cannot be inverted (or is not finite)", false},
      {"inverse-bind-mismatch", S::kWarning,
       "the inverse bind matrices match no pose of the skeleton: a joint bound away from where its parent's bind "
       "and its unanimated offset put it (the mesh tears there)",
       false},
      {"rest-differs-from-bind", S::kInfo, "a joint is posed at rest unlike its bind pose (legal)", false},
      {"joint-zero-scale", S::kWarning, "a joint matrix scales to zero at rest or at a key (its normals are undefined)",
       false},
      {"joint-mirrored", S::kWarning,
       "a joint matrix mirrors at rest or at a key (its triangles turn inside out; DQS cannot represent it)", false},
      {"joint-uniform-scale", S::kInfo,
       "a joint matrix has uniform scale, beyond the skin's own, at rest or at a key (DQS two-phase keeps it)", false},
      {"joint-nonuniform-scale", S::kWarning,
       "a joint matrix has non-uniform scale or shear at rest or at a key (three.js shades its normals wrong)", false},
      {"rotation-not-unit", S::kError,
       "a rotation key is not a unit quaternion (--fix normalizes it; a key of length 0 takes the nearest valid key "
       "of its channel, or the node's rest rotation)",
       true},
      {"hemisphere-flip", S::kWarning, "neighbouring rotation keys in opposite hemispheres (dot < 0)", true},
      {"duplicate-channel", S::kError,
       "two channels of one animation animate the same node and path with different keys (the commands that "
       "deform refuse the file; --fix keeps the first)",
       true},
      {"repeated-channel", S::kWarning,
       "a channel repeats an earlier one of its animation (the same node, path and keys): glTF 2.0 forbids it "
       "and the Khronos validator fails the file, though viewers play it (--fix removes it)",
       true},
      {"skinned-node-transform", S::kInfo,
       "skinned mesh nodes have a transform (their own or a parent's), which glTF ignores (§3.7.3.1)", false},
  };
  return checks;
}

LintSeverity LintFileResult::worst() const {
  LintSeverity w = LintSeverity::kInfo;
  if (!error.empty()) return LintSeverity::kError;
  for (const LintFinding& f : findings)
    if (f.severity > w) w = f.severity;
  return w;
}

bool LintFileResult::has(const std::string& check) const {
  for (const LintFinding& f : findings)
    if (f.check == check) return true;
  return false;
}

LintFileResult lint_file(const std::string& path, const LintOptions& options) {
  LintFileResult result;
  result.path = path;
  try {
    check_cancelled(options.cancel);
    const gltf::SkinData data = gltf::read_skin_data(path, options.load);
    lint::Findings found;
    check_cancelled(options.cancel);
    // What the loader reads but the deforming commands refuse (LoadOptions::refuse_undeformable): lint
    // describes the file and reports each as an error, the first one's message shown. Different duplicate
    // channels have their own check (duplicate-channel, which --fix repairs), so they are not counted twice.
    std::set<std::string> own_check;
    for (const gltf::DuplicateChannel& d : data.duplicate_channels)
      if (!d.identical) own_check.insert(d.message);
    for (const std::string& why : data.structure.cannot_deform)
      if (!own_check.count(why)) found["cannot-deform"].add(0, {why.substr(0, why.find(": "))}, [&why] { return why; });
    lint::check_influences(data, options, found);
    lint::check_skeletons(data, options, found);
    lint::check_rotation_keys(data, options, found);
    lint::check_channels(data, options, found);
    for (const LintCheckInfo& check : lint_checks()) {
      const auto it = found.find(check.id);
      if (it == found.end()) continue;
      const lint::Tally& t = it->second;
      result.findings.push_back({check.id, check.severity, t.count, printable(t.message), t.worst});
      result.findings.back().worst.where = printable(t.worst.where);
    }
  } catch (const InputError& e) {
    result.error = e.what();
  } catch (const std::bad_alloc&) {
    result.error = out_of_memory_message();
  } catch (const JobCancelled&) {
    throw;
  } catch (const std::exception& e) {
    // Whatever else a malformed file makes the reading throw is still this file's problem, named with it.
    result.error = e.what();
  }
  return result;
}

}  // namespace dqskin
