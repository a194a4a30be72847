// dqskin's command line, assembled: each command file declares its own flags and runs (commands.hpp);
// run_cli parses and runs the command named, through guarded_run. main() is compiled out (DQSKIN_NO_MAIN)
// of the CLI's fuzz target (fuzz/fuzz_cli.cpp), which calls run_cli itself, as gltfpack's fuzzer calls its
// main, and of the Python module (python/), which runs the commands in-process.
#include "commands.hpp"
#include "console.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"

#include "dqskin/memory_ceiling.hpp"
#include "dqskin/version.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

// The command line as run_cli parses it: every command's subcommand and flags in `app`.
std::vector<dqskin::cli::Command> build_app(CLI::App& app) {
  using namespace dqskin::cli;
  app.set_version_flag("--version", std::string("dqskin ") + dqskin::kVersion, "Print the version and exit");
  app.footer("Exit status: 0 success, 1 some inputs failed, 2 usage or input error, 3 no OpenGL context.\n"
             "Run 'dqskin COMMAND --help' for the options of a command.\n"
             "Examples:\n"
             "  dqskin info Fox.glb\n"
             "  dqskin bake Fox.glb -o out --format glb,vat\n"
             "  dqskin report Fox.glb -o reports\n"
             "  dqskin lint *.glb --junit lint.xml\n"
             "  dqskin optimize Fox.glb -o Fox.small.glb --max-error 0.1%\n"
             "  dqskin verify out\n"
             "  dqskin bench --quick");
  return {add_info_command(app), add_bench_command(app), add_bake_command(app),
          add_render_command(app), add_diff_command(app), add_report_command(app),
          add_lint_command(app), add_optimize_command(app), add_verify_command(app),
          add_merge_command(app)};
}

constexpr const char* kDescription =
    "dqskin: deforms the skinned meshes of glTF 2.0 animations with dual quaternions (Kavan et al.), "
    "headless, for asset builds and CI.";

}  // namespace

std::vector<dqskin::cli::OptionShape> dqskin::cli::command_options(const std::string& name) {
  CLI::App app{kDescription, "dqskin"};
  build_app(app);
  std::vector<OptionShape> shapes;
  for (const CLI::App* command : app.get_subcommands({}))
    if (command->get_name() == name)
      for (const CLI::Option* o : command->get_options()) {
        if (o->get_lnames().empty() || o->get_lnames().front() == "help") continue;
        shapes.push_back({o->get_lnames().front(), o->get_expected_max() == 0, o->get_items_expected_max() > 1});
      }
  return shapes;
}

int dqskin::cli::run_cli(int argc, const char* const* argv) {
  CLI::App app{kDescription, "dqskin"};
  const std::vector<Command> commands = build_app(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kSuccess;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << '\n';
    return kSuccess;
  } catch (const CLI::ParseError& e) {
    print_error(std::string(e.what()) + " (see dqskin --help)");
    return kUsageOrInputError;
  }
  for (const Command& command : commands)
    if (command.cli->parsed())
      return guarded_run(command.cli->get_name().c_str(), [&command] {
        // --max-memory holds for all the command does (dqskin/memory_ceiling.hpp); the ceiling is gone
        // again when guarded_run's handlers print what escaped.
        std::optional<MemoryCeiling> ceiling;
        if (const std::optional<uint64_t> bytes = max_memory_of(*command.cli)) ceiling.emplace(*bytes);
        return command.run();
      });
  // No command given: show what there is to run.
  std::cout << app.help();
  return kSuccess;
}

#ifndef DQSKIN_NO_MAIN
int main(int argc, char** argv) { return dqskin::cli::run_cli(argc, argv); }
#endif
