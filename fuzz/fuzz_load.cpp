// libFuzzer target for the loader and what `dqskin info` runs after it: bytes → load_asset_from_memory →
// describe, sample_pose at a few times of every clip, and the dqs deformation of every mesh instance of
// the chosen scene at one time. The only exception an input may cause is dqskin::InputError; anything
// else (another exception, a sanitizer report, a hang, a leak, an out-of-memory) is a finding.
//
// Besides fuzzing, DQSKIN_FUZZ_PREFIXES=FILE... (colon-separated) makes the binary feed the prefixes of
// each file (all of them up to 8 KiB), each in a fresh allocation of exactly its size, and exit:
// meshoptimizer's truncated-input idiom, so that AddressSanitizer catches any read past the end
// (scripts/check/fuzz.sh runs it on the seeds).
#include "dqskin/animation.hpp"
#include "dqskin/error.hpp"
#include "dqskin/info.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace {

// Work limits per input, so that a slow input means a slow loader, not a slow harness.
constexpr size_t kMaxVertices = 100000;          // total over all primitives; larger assets only load
constexpr size_t kMaxDeformedVertices = 400000;  // over all mesh instances of the scene
constexpr size_t kTimesPerClip = 4;
constexpr size_t kMaxClips = 8;

size_t total_vertices(const dqskin::Asset& asset) {
  size_t n = 0;
  for (const dqskin::Mesh& mesh : asset.meshes)
    for (const dqskin::Primitive& p : mesh.primitives) n += p.vertex_count();
  return n;
}

// What `dqskin info` and a bake do with a loaded asset, with bounded work.
void exercise(const dqskin::Asset& asset) {
  const dqskin::AssetFacts facts = dqskin::describe(asset);
  (void)facts;
  if (total_vertices(asset) > kMaxVertices) return;

  // Poses at the clip start, its first key, the middle and past the end (channels clamp there).
  for (size_t c = 0; c < std::min(asset.clips.size(), kMaxClips); ++c) {
    const dqskin::Clip& clip = asset.clips[c];
    const double times[kTimesPerClip] = {0.0, clip.first_key, 0.5 * (clip.first_key + clip.last_key),
                                         clip.last_key + 1.0};
    for (double t : times) {
      const dqskin::Pose pose = dqskin::sample_pose(asset, &clip, t);
      (void)pose;
    }
  }

  const int scene = dqskin::choose_scene(asset, -1);
  const std::vector<dqskin::MeshInstance> instances = dqskin::mesh_instances(asset, scene);
  const dqskin::Clip* clip = asset.clips.empty() ? nullptr : &asset.clips.front();
  const double time = clip ? 0.5 * (clip->first_key + clip->last_key) : 0.0;
  const dqskin::Pose pose = dqskin::sample_pose(asset, clip, time);
  std::vector<std::unique_ptr<dqskin::JointTransforms>> skins(asset.skins.size());
  size_t budget = kMaxDeformedVertices;
  for (const dqskin::MeshInstance& instance : instances) {
    const dqskin::JointTransforms* joints = nullptr;
    if (instance.skin >= 0) {
      auto& jt = skins[size_t(instance.skin)];
      if (!jt)
        jt = std::make_unique<dqskin::JointTransforms>(
            dqskin::joint_transforms(asset.skins[size_t(instance.skin)], pose));
      joints = jt.get();
    }
    const dqskin::Mesh& mesh = asset.meshes[size_t(instance.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const size_t n = mesh.primitives[p].vertex_count();
      if (n > budget) return;
      budget -= n;
      const dqskin::DeformedPrimitive out =
          dqskin::deform_primitive(asset, instance, p, pose, joints, dqskin::BlendMode::kDqs, 1);
      if (out.positions.size() != n) std::abort();  // the deformer keeps the vertex count
    }
  }
}

void run_one(const uint8_t* data, size_t size) {
  try {
    // Below libFuzzer's -rss_limit_mb with the sanitizers' overhead: an input over it is refused in words,
    // which is the behaviour under test, not an out-of-memory finding.
    dqskin::LoadOptions options;
    options.max_memory = uint64_t(256) << 20;
    const dqskin::Asset asset =
        dqskin::load_asset_from_memory(std::span<const uint8_t>(data, size), "fuzz", "/nonexistent-fuzz-dir", options);
    exercise(asset);
  } catch (const dqskin::InputError& e) {
    // The loader's promise: one line that says what is wrong.
    const std::string message = e.what();
    if (message.empty() || message.find('\n') != std::string::npos) {
      std::fprintf(stderr, "InputError message is empty or not one line: '%s'\n", message.c_str());
      std::abort();
    }
  }
}

// DQSKIN_FUZZ_PREFIXES: every prefix of each listed file, each in its own exactly sized allocation.
void run_prefixes(const char* list) {
  std::string files(list);
  size_t start = 0;
  while (start <= files.size()) {
    const size_t colon = std::min(files.find(':', start), files.size());
    const std::string path = files.substr(start, colon - start);
    start = colon + 1;
    if (path.empty()) continue;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "fuzz_load: cannot read %s\n", path.c_str());
      std::exit(1);
    }
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Every prefix of small files; of larger ones (mostly JSON, where each prefix costs a parse of its
    // whole length) the first and last kEdge and kSpread more spread evenly between.
    constexpr size_t kSmall = 8192, kEdge = 256, kSpread = 1024;
    const size_t size = bytes.size();
    const size_t step = size <= kSmall ? 1 : std::max<size_t>(1, size / kSpread);
    size_t tried = 0;
    for (size_t n = 0; n <= size; ++n) {
      if (!(n < kEdge || size - n < kEdge || n % step == 0)) continue;
      const std::unique_ptr<uint8_t[]> copy(new uint8_t[std::max<size_t>(n, 1)]);
      std::copy(bytes.begin(), bytes.begin() + std::ptrdiff_t(n), copy.get());
      run_one(copy.get(), n);
      ++tried;
    }
    std::fprintf(stderr, "fuzz_load: %zu of %zu prefixes of %s: no finding\n", tried, size + 1, path.c_str());
  }
  std::exit(0);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* list = std::getenv("DQSKIN_FUZZ_PREFIXES")) run_prefixes(list);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  run_one(data, size);
  return 0;
}
