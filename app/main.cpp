// dqskin command line: CLI11 fills one settings struct per command, one function runs it.
#include "commands.hpp"
#include "exit_codes.hpp"

#include "dqskin/version.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

int main(int argc, char** argv) {
  using namespace dqskin::cli;

  CLI::App app{
      "dqskin: deforms the skinned meshes of glTF 2.0 animations with dual quaternions (Kavan et al.), "
      "headless, for asset builds and CI.",
      "dqskin"};
  app.set_version_flag("--version", std::string("dqskin ") + dqskin::kVersion, "Print the version and exit");
  app.footer("Exit status: 0 success, 1 some inputs failed, 2 usage or input error, 3 no OpenGL context.\n"
             "Run 'dqskin COMMAND --help' for the options of a command.");

  InfoSettings info;
  CLI::App* info_cmd = app.add_subcommand(
      "info", "Print scenes, skinned meshes, skins, animations, morph targets and warnings of glTF files");
  info_cmd->add_option("FILE", info.inputs, ".gltf or .glb files")->required();
  info_cmd->add_flag("--json", info.json, "Print one JSON document instead of text");

  BenchSettings bench;
  CLI::App* bench_cmd = app.add_subcommand(
      "bench", "Measure vertex-frames per second of lbs, dqs and dqs with scale on the GPU path and the CPU "
               "reference, for synthetic characters of 10k, 100k and 1M vertices");
  bench_cmd->add_flag("--json", bench.json, "Print one JSON document: one entry per measurement");
  bench_cmd->add_flag("--quick", bench.quick, "A run under a minute: 10k and 100k vertices, 1 and 64 frames per batch");
  bench_cmd->add_option("--backend", bench.backend, "Headless OpenGL backend: auto (EGL, then OSMesa), egl or osmesa")
      ->capture_default_str();
  bench_cmd->add_option("--gpu-memory", bench.gpu_memory_mb, "GPU output buffer budget per batch, in MiB")
      ->capture_default_str()
      ->check(CLI::Range(size_t(1), size_t(1) << 20));

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kSuccess;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << '\n';
    return kSuccess;
  } catch (const CLI::ParseError& e) {
    std::cerr << "dqskin: " << e.what() << " (see dqskin --help)\n";
    return kUsageOrInputError;
  }

  if (info_cmd->parsed()) return run_info(info);
  if (bench_cmd->parsed()) return run_bench(bench);

  // No command given: show what there is to run.
  std::cout << app.help();
  return kSuccess;
}
