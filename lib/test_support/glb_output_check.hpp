// Test-only: reading a baked .glb frame back and checking it against its source and the deformed frame, as
// write/glb_output_test.cpp does, for inputs that other tests make too (the compressed ones of
// load/compression_test.cpp). Failures are GoogleTest failures.
#pragma once

#include "dqskin/deformed_batch.hpp"
#include "dqskin/frame_view.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dqskin::glb_check {

using nlohmann::json;

// The writer copies what the loader kept of the file.
const LoadOptions kKeepSource = [] {
  LoadOptions o;
  o.keep_source = true;
  return o;
}();

struct Glb {
  json doc;
  std::string bin;
};

// Checks the container of §4.4 and returns its chunks.
Glb parse_glb(const std::string& bytes);
// The values of an accessor the writer made (tightly packed, one view each), as double.
std::vector<double> read_accessor(const Glb& glb, int index);

// One CPU-reference frame of an asset in the middle of its first clip (rest pose without clips).
struct Frame {
  int scene = -1;
  std::vector<MeshInstance> instances;
  const Clip* clip = nullptr;
  double time = 0;
  DeformedBatch batch;
  FrameView view;
};
Frame mid_frame(const Asset& asset);

// The JSON of a .gltf or .glb file.
json source_json(const std::string& path);
// Writes `bytes` as NAME.glb into $DQSKIN_GLB_SAMPLE_DIR, when set (emptied once per process), for the
// Khronos glTF-Validator (CTest's glb_validator tests).
void keep_sample(const std::string& name, const std::string& bytes);

// What every frame must satisfy.
void expect_frame(const Asset& asset, const json& source, const Frame& f, const Glb& glb);

// Loads `path` keeping its source, writes its middle frame as a .glb twice and from several threads (all
// must be equal), checks it with expect_frame and keeps it as SAMPLE_NAME.glb (keep_sample).
void check_model(const std::string& path, const std::string& sample_name);

}  // namespace dqskin::glb_check
