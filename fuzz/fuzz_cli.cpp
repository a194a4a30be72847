// libFuzzer target for the command line as a user runs it: the input is a glTF file (.glb or .gltf by its
// first bytes), written into a scratch folder, and run_cli (app/main.cpp, compiled without main()) runs
// `dqskin info --json` and `dqskin lint --json` (with --fix for a third of the inputs) on it, then one of
// three bakes, chosen by the input's size so that mutations reach all of them: every format on the CPU
// reference, a dry run, and dib. Bakes run on the CPU reference (no GL context: libFuzzer needs a process
// that stays fast and deterministic) under --max-memory 32M, which bounds the work an input may ask for.
// A finding is a crash, a sanitizer report, an exception escaping run_cli, a hang, a leak, or an exit
// status other than 0, 1 (some inputs failed) and 2 (input error).
// What it cannot see: an unexpected std::exception inside one input becomes that input's error, as it
// does for users (fuzz_load, which calls the loader directly, treats anything but InputError as a finding).
#include "command_line.hpp"

using namespace dqskin::fuzz;

namespace {

void expect_status(int status) { dqskin::fuzz::expect_status("fuzz_cli", status); }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  keep_stderr();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool glb = size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  const std::string model = (scratch() / (glb ? "model.glb" : "model.gltf")).string();
  const std::string out = (scratch() / "out").string();
  {
    std::ofstream file(model, std::ios::binary);
    file.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  const std::vector<std::string> limits = {"--max-memory", "32M"};
  std::vector<std::string> info = {"info", "--json", model};
  info.insert(info.end(), limits.begin(), limits.end());
  expect_status(run(info));

  // lint reads what the loader refuses (joints out of range, negative weights); --fix writes it back.
  std::vector<std::string> lint = {"lint", "--json", model};
  if (size % 3 == 0) lint.insert(lint.end(), {"--fix", "-o", (scratch() / "fixed.glb").string()});
  lint.insert(lint.end(), limits.begin(), limits.end());
  expect_status(run(lint));

  std::vector<std::string> bake = {"bake", model, "-o", out, "--backend", "cpu", "-q"};
  switch (size % 3) {
    case 0:
      bake.insert(bake.end(), {"--format", "glb,ply,obj,vat,bones", "--frames", "0:1", "--fps", "4", "-j", "1"});
      break;
    case 1:
      bake.insert(bake.end(), {"--format", "glb,ply,obj,vat,bones", "--dry-run"});
      break;
    default:
      bake.insert(bake.end(), {"--format", "ply", "--mode", "dib", "--frames", "0:0", "-j", "1"});
      break;
  }
  bake.insert(bake.end(), limits.begin(), limits.end());
  expect_status(run(bake));

  std::error_code ignored;
  fs::remove_all(out, ignored);
  fs::remove(model, ignored);
  fs::remove(scratch() / "fixed.glb", ignored);
  return 0;
}
