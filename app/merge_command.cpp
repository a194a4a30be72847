// `dqskin merge OUTDIR`: the shard manifests of a sharded bake or render, after all shards have run into
// OUTDIR, into the manifest the unsharded job writes (dqskin/verify.hpp merge_shards): what a Make rule
// or a pipeline step whose target is manifest.json waits for.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "interrupt.hpp"

#include "../lib/base/byte_size.hpp"
#include "dqskin/error.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "dqskin/verify.hpp"

#include <algorithm>
#include <iostream>
#include <memory>
#include <new>

namespace dqskin::cli {
namespace {

struct MergeSettings {
  std::string folder;
  bool quiet = false;
  unsigned threads = 0;
  std::string max_memory = "2G";  // run_cli's MemoryCeiling: a manifest of millions of entries is refused
};

// Prints the refusal's problems, or what was merged, on stderr; returns the exit status.
int print_report(const MergeSettings& settings, const MergeReport& report) {
  MergeSettings s = settings;
  s.folder = report.verify.folder;  // as messages name it (no trailing slash)
  // A folder far from its manifests (an unmerged folder copied half, a stale shard) can have thousands of
  // problems: the first ones say what is wrong, dqskin verify lists them all. Beside a shard that did not
  // finish, the files no manifest lists are most likely its own, which it keeps when run again: one line.
  const std::vector<FolderProblem>& problems = report.verify.problems;
  const bool unfinished = std::any_of(problems.begin(), problems.end(), [](const FolderProblem& p) { return p.kind == "shard-missing"; });
  constexpr size_t kShown = 20;
  size_t shown = 0, unlisted = 0;
  for (const FolderProblem& p : problems) {
    if (unfinished && p.kind == "unlisted") ++unlisted;
    else if (shown++ < kShown) print_error(problem_location(s.folder, p), p.message);
  }
  if (shown > kShown)
    print_error(s.folder, "and " + std::to_string(shown - kShown) + " more problems (dqskin verify lists them all)");
  if (unlisted > 0)
    print_error(s.folder, std::to_string(unlisted) + " files that no manifest lists, most likely the unfinished shards' " +
                              "(a shard run again keeps those that are right)");
  for (const std::string& r : report.refusals) print_error(r);
  if (!report.ok()) {
    const size_t count = report.verify.problems.size() + report.refusals.size();
    print_error(s.folder, "merge refused, nothing written (" + std::to_string(count) + (count == 1 ? " problem)" : " problems)"));
    return kUsageOrInputError;
  }
  if (!s.quiet) {
    const std::string files = std::to_string(report.verify.files) + " files (" + byte_size(report.verify.bytes) + ")";
    if (report.merged.empty())
      std::cerr << "nothing to merge in " << printable(s.folder) << ": no shard manifests; " << files << " as listed\n";
    for (const MergedJob& m : report.merged)
      std::cerr << "merged " << m.shards << " shards into " << printable(s.folder + "/" + m.manifest) << ": " << files
                << " verified\n";
  }
  // As the unsharded bake: an input that failed (in every shard alike) is named, and the status says so.
  for (const auto& [input, error] : report.failed_inputs) print_error(input, error + " (in every shard)");
  return report.failed_inputs.empty() ? kSuccess : kSomeInputsFailed;
}

// Merges and prints what happened. A signal stops it with the folder as it was (merge_shards swaps the
// manifests all at once); so does a refusal of --max-memory, whose one line names the folder (a manifest
// too large to read is named by the library).
int run_merge(const MergeSettings& s) {
  try {
    return print_report(s, merge_shards(s.folder, s.threads, catch_interrupts("merge")));
  } catch (const std::bad_alloc&) {
    const MemoryCeilingLifted lifted;  // the merge's memory is freed; the message allocates
    print_error(problem_location(s.folder, {}), out_of_memory_message());
    return kUsageOrInputError;
  }
}

}  // namespace

Command add_merge_command(CLI::App& app) {
  auto settings = std::make_shared<MergeSettings>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "After every shard of a bake or render (--shard I/N) has run into OUTDIR: verify their files and "
               "write the manifest the unsharded run writes, byte for byte");
  cmd->add_option("OUTDIR", settings->folder, "The folder the shards wrote (-o)")->required();
  cmd->add_option("--threads", settings->threads, "Files hashed at once (default: one per core)")->type_name("N");
  cmd->add_flag("-q,--quiet", settings->quiet, "Print nothing unless the merge is refused");
  add_max_memory(*cmd, settings->max_memory);
  cmd->footer(
      "Reads manifest.shard-I-of-N.json (bake) and render-manifest.shard-I-of-N.json (render), checks the\n"
      "folder as dqskin verify does, checks that all N shards finished with the same flags, inputs (by\n"
      "SHA-256) and deformer, then writes manifest.json (render-manifest.json) and deletes the shard manifests.\n"
      "Refuses, writing nothing, with one line per problem: a shard that did not finish (run it again: it\n"
      "keeps the files already there and removes what a killed run left), a file missing or changed, shards\n"
      "run differently. With no shard manifests and a folder as its manifests say, there is nothing to do.\n"
      "Exit status: 0 merged (or nothing to merge), 1 merged but some inputs failed in every shard (each named),\n"
      "2 refused or a usage error.\n"
      "Examples:\n"
      "  parallel dqskin bake models/*.glb -o out --shard {}/8 --quiet ::: $(seq 0 7) && dqskin merge out");
  return {cmd, [settings] { return run_merge(*settings); }};
}

}  // namespace dqskin::cli
