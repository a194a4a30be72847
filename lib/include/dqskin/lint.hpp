// `dqskin lint`: skin-data problems of glTF files (weights, influences, joints, skeletons, inverse bind
// matrices, joint matrices, rotation keys), each reported once per file with its count, the worst example
// and a severity; and `--fix`, a corrected copy of a file. Plain data: no JSON or tinygltf type.
#pragma once

#include "dqskin/load.hpp"

#include <atomic>
#include <cstddef>
#include <string>
#include <vector>

namespace dqskin {

enum class LintSeverity { kInfo, kWarning, kError };
const char* to_string(LintSeverity severity);  // "info", "warning", "error"

struct LintOptions {
  // Weights of a vertex (over every WEIGHTS_n) may sum to 1 ± sum_tolerance; with normalized integers at
  // least ± n·0.5/255 (or /65535) for n nonzero weights, what rounding each stored weight allows.
  double sum_tolerance = 1e-3;
  // More nonzero weights per vertex than this is a warning (and what --fix keeps, at most kMaxInfluences):
  // too-many-influences up to 8, over-8-influences past them (runtimes that read 8 drop the rest).
  int max_influences = 4;
  // As a share of the skeleton's size (the bounding-box diagonal of the joints' bind positions, in bind
  // space): how far a joint may be bound from where its parent's bind transform and its rest offset put it
  // (inverse-bind-mismatch), and how far the rest pose may be from the bind pose before it is noted
  // (rest-differs-from-bind: largest entry of placement⁻¹ · world · inverseBind − I, translations over the
  // size).
  double bind_tolerance = 1e-3;
  // Scale or shear of joint matrices relative to the skin's placement scale: entries of S − I or S − sI
  // (A = R S) beyond this; a smallest scale below it is a zero scale. Looser than docs/DESIGN.md §9.3's 1e-5: float
  // matrices composed down a chain of joints carry about 1e-5 of rounding.
  double scale_tolerance = 1e-4;
  // Rotation keys whose length differs from 1 by more than this.
  double unit_tolerance = 1e-3;
  LoadOptions load;
  // Set from a signal handler: lint_file and lint_fix stop at their next check with JobCancelled, lint_fix
  // before its output is under its name (the temporary is removed).
  const std::atomic<bool>* cancel = nullptr;
};

// The single worst case of a finding. Fields that do not apply are -1.
struct LintExample {
  std::string where;  // "mesh 0 primitive 1", "skin 0", "animation 'Walk' channel 3"
  long long vertex = -1;
  long long joint = -1;  // as stored in JOINTS_n, or the skin's joint index
  long long key = -1;
  double value = 0;  // what the check measures (a sum, a count, a deviation, a length, a dot product)
};

struct LintFinding {
  std::string check;  // a stable id: "weight-sum", "hemisphere-flip", … (lint_checks() lists them)
  LintSeverity severity = LintSeverity::kWarning;
  size_t count = 0;     // vertices, joints, matrices or keys with the problem
  std::string message;  // one line: what is wrong with the worst example, for people
  LintExample worst;
};

// One file: its findings in lint_checks() order, or why it could not be read.
struct LintFileResult {
  std::string path;
  std::string error;  // non-empty: unreadable or malformed; no findings
  std::vector<LintFinding> findings;
  LintSeverity worst() const;  // kInfo when clean
  bool has(const std::string& check) const;
};

// Every check: its id, its severity, what it looks for and whether --fix corrects it.
struct LintCheckInfo {
  const char* id;
  LintSeverity severity;
  const char* what;
  bool fixable;
};
const std::vector<LintCheckInfo>& lint_checks();

// Lints one file. Never throws for a bad input: its message goes into `error`. Throws JobCancelled when
// options.cancel is set.
LintFileResult lint_file(const std::string& path, const LintOptions& options);

// What --fix changed, for the report.
struct LintFixSummary {
  size_t primitives = 0;       // primitives whose influences were rewritten
  size_t rotation_tracks = 0;  // rotation samplers whose keys were rewritten
  size_t skeletons = 0;        // skins whose wrong `skeleton` property was removed
  size_t channels = 0;         // animation channels removed (the later ones of channels sharing a target)
};

// Writes a corrected copy of `input` to `output` (.glb, atomically): influences merged per joint, negative
// weights and joints beyond every skin that draws the mesh dropped (one that fits a larger skin only is
// kept), sorted by weight and cut to options.max_influences (at most kMaxInfluences), a vertex without
// weight bound to the joint nearest to it in bind space, renormalized in the original component type
// (normalized integers summing exactly to 255 or 65535); rotation keys made unit and
// hemisphere-consistent; a `skeleton` that is not the joints' common root removed; of channels of one
// animation with the same target, all but the first removed. What it cannot fix
// (joints without a common root, inverse bind matrices, joint scale) stays. Throws InputError for an input
// it cannot read or rewrite faithfully (compressed data) or whose rewrite would take more than
// options.load.max_memory, OutputError when the output cannot be written, JobCancelled when
// options.cancel is set (no output then).
LintFixSummary lint_fix(const std::string& input, const std::string& output, const LintOptions& options);

// Reports, in the conventions of `dqskin diff` (diff_report.hpp). Text: per file "FILE: STATUS" (clean,
// info, warning, error) then "  SEVERITY CHECK (COUNT): MESSAGE" per finding, then "summary: STATUS (N files:
// …)". JSON: one document {"files": [{file, status, findings: [{check, severity, count, message, worst:
// {where, vertex, joint, key, value}}]} or {file, status, problem}], "options", "summary"}, fields that do
// not apply null. JUnit XML: a testcase per file and check (one per unreadable file), a <failure> for an
// error, warnings and information in <system-out>. Same results, same bytes.
std::string lint_text(const std::vector<LintFileResult>& results);
std::string lint_json(const std::vector<LintFileResult>& results, const LintOptions& options);
std::string lint_junit(const std::vector<LintFileResult>& results);

}  // namespace dqskin
