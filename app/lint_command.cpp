// `dqskin lint FILE...`: skin-data problems of glTF files (dqskin/lint.hpp), reported as text, JSON or
// JUnit XML in the conventions of `dqskin diff`, with diff's exit statuses (0 clean, 1 warnings, 2 errors);
// `--fix -o OUT.glb` writes a corrected copy and lints it again.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"
#include "interrupt.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "dqskin/lint.hpp"
#include "dqskin/memory_ceiling.hpp"

#include <iostream>
#include <memory>
#include <new>

namespace dqskin::cli {
namespace {

struct LintSettings {
  std::vector<std::string> inputs;
  LintOptions options;
  bool json = false;
  std::string junit;  // JUnit XML report; none when empty
  bool werror = false;
  bool fix = false;
  std::string output;  // --fix's .glb
  LoadSettings load;
};

// As diff: 0 clean (or information only), 1 warnings, 2 errors or an unreadable file; --werror makes
// warnings errors.
constexpr int kLintWarn = 1;
constexpr int kLintFail = 2;
static_assert(kLintFail == kUsageOrInputError);

int exit_status(const std::vector<LintFileResult>& results, bool werror) {
  int status = kSuccess;
  for (const LintFileResult& r : results) {
    const LintSeverity w = r.worst();
    if (w == LintSeverity::kError || (w == LintSeverity::kWarning && werror)) return kLintFail;
    if (w == LintSeverity::kWarning) status = kLintWarn;
  }
  return status;
}

int run_lint(LintSettings& s) {
  LintOptions& o = s.options;
  if (!(o.sum_tolerance >= 0)) throw InputError("--sum-tolerance must be 0 or more");
  if (o.max_influences < 1) throw InputError("--max-influences must be 1 or more");
  if (!(o.bind_tolerance >= 0)) throw InputError("--bind-tolerance must be 0 or more");
  if (!(o.scale_tolerance >= 0)) throw InputError("--scale-tolerance must be 0 or more");
  if (!(o.unit_tolerance >= 0)) throw InputError("--unit-tolerance must be 0 or more");
  if (s.fix != !s.output.empty()) throw InputError("--fix and -o go together: dqskin lint --fix IN -o OUT.glb");
  if (s.fix && s.inputs.size() != 1) throw InputError("--fix takes one input (it writes one output, -o)");
  if (s.fix && s.output.size() < 4) throw InputError("-o must name a .glb file");
  if (s.fix && s.output.substr(s.output.size() - 4) != ".glb") throw InputError("-o must name a .glb file");
  o.load = to_load_options(s.load);
  o.load.refuse_undeformable = false;  // lint reports what stops a deformation as an error (cannot-deform)
  // SIGINT and SIGTERM stop lint as they stop bake: one line, the process ends by the signal, and --fix
  // leaves neither its temporary nor a partial output (interrupt.hpp).
  o.cancel = catch_interrupts("lint");

  std::vector<LintFileResult> results;
  for (const std::string& input : s.inputs) results.push_back(lint_file(input, o));
  // A fix that cannot be made (an input it cannot rewrite faithfully, an output that cannot be written) is
  // one line; the input's report is still printed, and the status is 2.
  bool fix_failed = s.fix && !results.front().error.empty();
  if (s.fix && !fix_failed) {
    try {
      const LintFixSummary fixed = lint_fix(s.inputs.front(), s.output, o);
      std::cerr << "dqskin: lint: wrote " << printable(s.output) << " (influences of " << fixed.primitives
                << " primitives and keys of " << fixed.rotation_tracks << " rotation samplers rewritten, "
                << fixed.skeletons << " skeleton properties and " << fixed.channels
                << " duplicate animation channels removed); linted again:\n";
      results.push_back(lint_file(s.output, o));
    } catch (const JobCancelled&) {
      throw;
    } catch (const InputError& e) {
      print_error(s.inputs.front(), std::string("--fix: ") + e.what());
      fix_failed = true;
    } catch (const OutputError& e) {
      check_cancelled(o.cancel);  // a stop that removed the temporary under the write: the stop's line only
      print_error(e.what());
      fix_failed = true;
    } catch (const std::bad_alloc&) {
      // The fix's memory is freed by now; the message is made without the ceiling, as guarded_run does.
      const MemoryCeilingLifted lifted;
      print_error(s.inputs.front(), "--fix: " + out_of_memory_message());
      fix_failed = true;
    } catch (const std::exception& e) {
      print_error(s.inputs.front(), std::string("--fix: ") + e.what());
      fix_failed = true;
    }
  }
  for (const LintFileResult& r : results)
    if (!r.error.empty()) print_error(r.path, r.error);
  std::cout << (s.json ? lint_json(results, o) : lint_text(results)) << std::flush;
  if (!s.junit.empty()) {
    AtomicFile junit(s.junit);
    junit.write(lint_junit(results));
    junit.commit(Overwrite::kReplace);
  }
  if (fix_failed) return kLintFail;
  // With --fix the verdict is the fixed file's: what remains after fixing.
  if (s.fix && results.size() == 2) return exit_status({results.back()}, s.werror);
  return exit_status(results, s.werror);
}

std::string checks_table() {
  std::string t = "Checks (severity; fixed by --fix):\n";
  for (const LintCheckInfo& c : lint_checks()) {
    std::string id = c.id;
    id.resize(24, ' ');
    std::string severity = to_string(c.severity);
    severity.resize(8, ' ');
    t += "  " + id + severity + (c.fixable ? "fixed  " : "       ") + c.what + "\n";
  }
  return t;
}

}  // namespace

Command add_lint_command(CLI::App& app) {
  auto settings = std::make_shared<LintSettings>();
  LintSettings& lint = *settings;
  LintOptions& o = lint.options;
  CLI::App* cmd = app.add_subcommand(
      "lint",
      "Report skin-data problems of glTF files: weights, influences, joints, skeletons, inverse bind matrices, "
      "joint scale, rotation keys; --fix writes a corrected copy");
  cmd->add_option("FILE", lint.inputs, "glTF files (.gltf, .glb)")->required();
  cmd->add_option("--sum-tolerance", o.sum_tolerance,
                  "A vertex's weights may sum to 1 ± this (normalized integers: at least their rounding, n·0.5/255 "
                  "or n·0.5/65535 for n weights)")
      ->type_name("X")
      ->capture_default_str();
  cmd->add_option("--max-influences", o.max_influences,
                  "More joints with weight per vertex is a warning (three.js reads 4, Babylon.js 8); --fix keeps "
                  "this many (1-32; 8 keeps JOINTS_1), as bake --max-influences N deforms")
      ->type_name("N")
      ->capture_default_str();
  cmd->add_option("--bind-tolerance", o.bind_tolerance,
                  "A joint bound this share of the skeleton's size (bind positions' bounding-box diagonal) from where "
                  "its parent's bind and its rest offset put it is a warning; a rest pose this far from the bind "
                  "pose is noted")
      ->type_name("X")
      ->capture_default_str();
  cmd->add_option("--scale-tolerance", o.scale_tolerance,
                  "Scale or shear of joint matrices, relative to the skin's placement: entries of S − I beyond this "
                  "(a smallest scale below it is a zero scale)")
      ->type_name("X")
      ->capture_default_str();
  cmd->add_option("--unit-tolerance", o.unit_tolerance,
                  "Rotation keys whose length is further from 1 (normalized integers: at least their rounding)")
      ->type_name("X")
      ->capture_default_str();
  cmd->add_flag("--werror", lint.werror, "Warnings are errors (exit status 2)");
  cmd->add_flag("--fix", lint.fix, "Write a corrected copy of the one input to -o, then lint it again");
  cmd->add_option("-o,--output", lint.output, "--fix's output (.glb, written atomically)")->type_name("OUT.glb");
  add_load_settings(*cmd, lint.load);
  cmd->add_flag("--json", lint.json, "Print one JSON document instead of text");
  cmd->add_option("--junit", lint.junit, "Also write a JUnit XML report, one testcase per file and check, to FILE")
      ->type_name("FILE");
  cmd->footer(
      checks_table() +
      "--fix merges a joint's influences, drops negative weights and joints out of range, sorts by weight, keeps\n"
      "--max-influences and renormalizes in the original component type (normalized integers sum exactly to\n"
      "255 or 65535), binds a vertex without weight to its nearest joint; it makes rotation keys unit and\n"
      "hemisphere-consistent (CUBICSPLINE tangents with them) and removes a skeleton that is not a common root.\n"
      "Joints without a common root, inverse bind matrices and joint scale are reported, not changed.\n"
      "The report then has the input and the fixed file; the exit status is the fixed file's.\n"
      "Exit status: 0 clean or information only, 1 warnings, 2 errors, an unreadable file, or a usage error.\n"
      "Examples:\n"
      "  dqskin lint *.glb --junit lint.xml\n"
      "  dqskin lint Fox.glb --json --max-influences 8\n"
      "  dqskin lint --fix character.gltf -o character.fixed.glb");
  // main.cpp runs it through guarded_run, so whatever escapes ends in one line and exit status 2.
  return {cmd, [settings] { return run_lint(*settings); }};
}

}  // namespace dqskin::cli
