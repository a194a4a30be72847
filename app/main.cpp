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
             "Run 'dqskin COMMAND --help' for the options of a command.\n"
             "Examples:\n"
             "  dqskin info Fox.glb\n"
             "  dqskin bake Fox.glb -o out --format glb,vat\n"
             "  dqskin bench --quick");

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

  BakeSettings bake;
  CLI::App* bake_cmd = app.add_subcommand(
      "bake", "Deform whole animations and write per-frame meshes (glb, ply, obj), vertex-animation textures "
              "(vat) and bone textures (bones), with a manifest of every file's SHA-256");
  bake_cmd->add_option("INPUT", bake.inputs,
                       ".gltf or .glb files. Without any, the bundled twisted_cylinder rig is baked into a new "
                       "temporary folder, which is printed");
  bake_cmd->add_option("-o,--out", bake.out_dir, "Output folder (created when missing)")->type_name("OUTDIR");
  bake_cmd->add_option("--anim", bake.anim, "Animation to bake: all, a name, or an index")
      ->type_name("NAME|INDEX|all")
      ->capture_default_str();
  bake_cmd->add_option("--fps", bake.fps, "Frames per second of the sampling grid; frame i is at i/fps seconds")
      ->type_name("FPS")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  bake_cmd->add_option("--frames", bake.frames, "Only grid frames A to B inclusive, every step-th")->type_name("A:B[:step]");
  bake_cmd->add_flag("--keys", bake.keys, "Sample every key time of the animation instead of the fps grid");
  bake_cmd->add_option("--times", bake.times, "Sample these times in seconds instead of the fps grid")->type_name("T,T,...");
  bake_cmd->add_option("--mode", bake.mode, "Blending: lbs (linear), dqs (dual quaternion DLB), dib (iterative, CPU)")
      ->type_name("lbs|dqs|dib")
      ->capture_default_str();
  bake_cmd->add_option("--format", bake.formats, "Outputs, any of glb,ply,obj,vat,bones (comma-separated)")
      ->type_name("LIST")
      ->capture_default_str();
  bake_cmd->add_option("--backend", bake.backend,
                       "Deformer: auto (EGL, then OSMesa), egl, osmesa, or cpu (the double-precision reference)")
      ->type_name("NAME")
      ->capture_default_str();
  bake_cmd->add_option("--scene", bake.scene, "Scene index (default: the file's default scene)")->type_name("INDEX");
  bake_cmd->add_option("--shard", bake.shard,
                       "Bake only shard I of N of the (input, animation, frame) work; the N shards' outputs "
                       "together equal the whole bake")
      ->type_name("I/N");
  bake_cmd->add_option("-j,--jobs", bake.jobs, "Encoder threads (default: one per core)")
      ->type_name("N")
      ->check(CLI::Range(1u, 1024u));
  bake_cmd->add_option("--gpu-memory", bake.gpu_memory_mb, "GPU output buffer budget, in MiB")
      ->type_name("MIB")
      ->capture_default_str()
      ->check(CLI::Range(size_t(1), size_t(1) << 20));
  bake_cmd->add_flag("-n,--dry-run", bake.dry_run, "List the files that would be written; write nothing");
  bake_cmd->add_flag("-q,--quiet", bake.quiet, "Print nothing but errors");
  bake_cmd->add_flag("--json-progress", bake.json_progress,
                     "Print progress and the final summary as JSON lines on standard output");
  bake_cmd->add_flag("-f,--force", bake.force,
                     "Overwrite existing outputs that differ (without it they are an error; equal ones are kept)");
  bake_cmd->add_flag("-v,--verbose", bake.verbose, "Also print the OpenGL backend and renderer");
  bake_cmd->footer(
      "Outputs: OUTDIR/<input name>/<animation>/frame_NNNN.{glb,ply,obj} (frame numbers zero-padded, so name order is\n"
      "frame order), materials.mtl, vat_positions.exr, vat_normals.exr, vat.json, bones_skinK.{exr,json}, and\n"
      "OUTDIR/manifest.json (manifest.shard-I-of-N.json for a shard). Files appear complete or not at all.\n"
      "Exit status: 0 success, 1 some inputs failed (the others baked), 2 usage or input error, 3 no OpenGL context.\n"
      "Examples:\n"
      "  dqskin bake Fox.glb -o out --format glb,vat\n"
      "  dqskin bake *.glb -o out --fps 24 --frames 0:47 --mode lbs\n"
      "  dqskin bake *.glb -o out --shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT");

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
  if (bake_cmd->parsed()) return run_bake(bake);

  // No command given: show what there is to run.
  std::cout << app.help();
  return kSuccess;
}
