// Test-only (dqskin_pipeline_tests): the checks glb_output_test.cpp makes of a frame written from a file,
// for inputs that other tests make, such as the compressed ones of gltf/compression_test.cpp.
#pragma once

#include <string>

namespace dqskin {

// Loads `path` keeping its source, writes its middle frame as a .glb (the same on every encode and
// thread), checks it against the source and the deformed frame, and keeps it as SAMPLE_NAME.glb in
// $DQSKIN_GLB_SAMPLE_DIR for the glb_validator test. Failures are gtest failures.
void check_glb_frame(const std::string& path, const std::string& sample_name);

}  // namespace dqskin
