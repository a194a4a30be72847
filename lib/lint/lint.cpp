// `dqskin lint` over one file: read its raw skin data, run every group of checks, and turn their tallies
// into findings in the catalogue's order (lint_checks()).
#include "dqskin/lint.hpp"

#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "lint_checks.hpp"

#include <new>

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
      {"inverse-bind-mismatch", S::kWarning,
       "an inverse bind matrix is not the inverse of the joint's rest world matrix", false},
      {"ibm-not-orthonormal", S::kWarning, "an inverse bind matrix has scale or shear", false},
      {"joint-uniform-scale", S::kInfo, "a joint matrix has uniform scale at rest or at a key (DQS two-phase keeps it)",
       false},
      {"joint-nonuniform-scale", S::kWarning, "a joint matrix has non-uniform scale or shear at rest or at a key",
       false},
      {"rotation-not-unit", S::kError,
       "a rotation key is not a unit quaternion (--fix normalizes it; a key of length 0 takes the nearest valid key "
       "of its channel, or the node's rest rotation)",
       true},
      {"hemisphere-flip", S::kWarning, "neighbouring rotation keys in opposite hemispheres (dot < 0)", true},
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
    lint::check_influences(data, options, found);
    lint::check_skeletons(data, options, found);
    lint::check_rotation_keys(data, options, found);
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
