// libFuzzer target for the manifests that bake and render write and that `dqskin verify` and `dqskin merge`
// read: the input is a manifest (manifest.json, or a shard's manifest.shard-0-of-2.json for inputs of odd
// size), alone in a scratch folder beside the one small file a seed lists. verify reads it and checks the
// folder against it; merge then assembles the shards' manifests. Both under --max-memory 32M.
#include "command_line.hpp"

using namespace dqskin::fuzz;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  keep_stderr();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path folder = scratch() / "bake";
  std::error_code ignored;
  fs::remove_all(folder, ignored);
  fs::create_directories(folder / "clip");
  write_file(folder / (size % 2 ? "manifest.shard-0-of-2.json" : "manifest.json"), data, size);
  { std::ofstream(folder / "clip" / "frame_0.ply") << "ply\n"; }  // a listed file for entries to find
  expect_status("fuzz_manifest", run({"verify", folder.string(), "--max-memory", "32M", "--quiet"}));
  expect_status("fuzz_manifest", run({"verify", folder.string(), "--max-memory", "32M", "--json"}));
  expect_status("fuzz_manifest", run({"merge", folder.string(), "--max-memory", "32M", "--quiet"}));
  fs::remove_all(folder, ignored);
  return 0;
}
