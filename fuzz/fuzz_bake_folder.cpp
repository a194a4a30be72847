// libFuzzer target for the bake folders that `dqskin diff A B` compares: A is a bake of the twisted
// cylinder (two frames as glb, ply and obj, and its VAT textures and vat.json, with the manifest), made
// once; B is a copy of A in which one file, chosen by the input's size, is replaced by the input. diff
// reads every file of both, under --max-memory 32M, writing its JSON report: a file that lies about its
// size, its counts or its contents must end in one line naming it, never a crash or a quoted secret.
#include "command_line.hpp"

#include <algorithm>

using namespace dqskin::fuzz;

namespace {

// A's files, relative to it, sorted: the ones an input may take the place of.
const std::vector<fs::path>& reference_files() {
  static const std::vector<fs::path> files = [] {
    const fs::path a = scratch() / "a";
    run({"bake", DQSKIN_FUZZ_TESTDATA "/twisted_cylinder.gltf", "-o", a.string(), "--format", "ply,obj,glb,vat",
         "--frames", "0:1", "--backend", "cpu", "-j", "1", "--quiet"});
    std::vector<fs::path> out;
    for (const auto& entry : fs::recursive_directory_iterator(a))
      if (entry.is_regular_file()) out.push_back(fs::relative(entry.path(), a));
    std::sort(out.begin(), out.end());
    if (out.empty()) std::abort();  // the bake that every input is compared with could not be made
    return out;
  }();
  return files;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  keep_stderr();
  reference_files();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path a = scratch() / "a", b = scratch() / "b";
  std::error_code ignored;
  fs::remove_all(b, ignored);
  fs::copy(a, b, fs::copy_options::recursive);
  const fs::path& replaced = reference_files()[size % reference_files().size()];
  write_file(b / replaced, data, size);
  expect_status("fuzz_bake_folder",
                run({"diff", a.string(), b.string(), "--max-memory", "32M", "--json"}));
  fs::remove_all(b, ignored);
  return 0;
}
