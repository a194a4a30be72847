// `dqskin verify OUTDIR`: a bake or render folder against its manifests (dqskin/verify.hpp), one line per
// problem on stdout (or --json), exit status 0 when the folder is what its manifests say, 2 otherwise.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "interrupt.hpp"

#include "../lib/base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "dqskin/verify.hpp"

#include <iostream>
#include <memory>
#include <new>

namespace dqskin::cli {
namespace {

struct VerifySettings {
  std::string folder;
  bool json = false;
  bool quiet = false;
  unsigned threads = 0;
  std::string max_memory = "2G";  // run_cli's MemoryCeiling: a manifest of millions of entries is refused
};

// Prints the problems (stdout) and the summary line (stderr); returns the exit status.
int print_report(const VerifySettings& s, const VerifyReport& report) {
  if (s.json) {
    std::cout << verify_json(report) << std::flush;
  } else {
    for (const FolderProblem& p : report.problems) std::cout << printable(problem_location(s.folder, p) + ": " + p.message) << '\n';
    std::cout << std::flush;
  }
  if (!s.quiet && !s.json) {
    std::string manifests;
    for (const std::string& m : report.manifests) manifests += (manifests.empty() ? "" : ", ") + m;
    std::cerr << printable(report.folder) << ": " << report.files << " files (" << byte_size(report.bytes) << ") listed by "
              << (manifests.empty() ? std::string("no manifest") : printable(manifests)) << ": "
              << (report.ok() ? std::string("all as listed") : std::to_string(report.problems.size()) + (report.problems.size() == 1 ? " problem" : " problems"))
              << '\n';
  }
  return report.ok() ? kSuccess : kUsageOrInputError;
}

// Checks the folder and prints what it found. A signal stops it (it writes nothing). When the files listed
// and the problems found take more than --max-memory, the one line names the folder (a manifest too large
// to read is named by the library).
int run_verify(const VerifySettings& s) {
  try {
    return print_report(s, verify_folder(s.folder, s.threads, catch_interrupts("verify")));
  } catch (const std::bad_alloc&) {
    const MemoryCeilingLifted lifted;  // the report's memory is freed; the message allocates
    print_error(problem_location(s.folder, {}), out_of_memory_message());
    return kUsageOrInputError;
  }
}

}  // namespace

Command add_verify_command(CLI::App& app) {
  auto settings = std::make_shared<VerifySettings>();
  CLI::App* cmd = app.add_subcommand(
      "verify", "Check a bake or render folder against its manifests: every listed file there with its size and "
                "SHA-256, no unlisted file, no leftover temporary, every shard finished");
  cmd->add_option("OUTDIR", settings->folder, "The folder bake or render wrote (-o)")->required();
  cmd->add_flag("--json", settings->json, "Print one JSON document instead of lines");
  cmd->add_option("--threads", settings->threads, "Files hashed at once (default: one per core)")->type_name("N");
  cmd->add_flag("-q,--quiet", settings->quiet, "No summary line on stderr");
  add_max_memory(*cmd, settings->max_memory);
  cmd->footer(
      "A problem per line, OUTDIR/PATH: what is wrong: a listed file missing, of another size (truncated or\n"
      "grown) or with other bytes (SHA-256); a file in an input's output folder that no manifest lists; a\n"
      "temporary (.NAME.tmp-PID-N) or old file (.NAME.old-PID-N) left by a process that was killed; a shard\n"
      "manifest (manifest.shard-I-of-N.json) missing while others of its job are there; a manifest that\n"
      "cannot be read. The manifests are manifest.json (bake), render-manifest.json (render) and their shards'.\n"
      "Exit status: 0 the folder is as its manifests say, 2 a problem or a usage error.\n"
      "Examples:\n"
      "  dqskin verify out\n"
      "  dqskin verify out --json > verify.json");
  return {cmd, [settings] { return run_verify(*settings); }};
}

}  // namespace dqskin::cli
