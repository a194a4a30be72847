// Test models by name (header-only, for the test executables, which define DQSKIN_TESTDATA_DIR and
// DQSKIN_SHARED_TESTDATA_DIR): a bundled rig of testdata/ ("twisted_cylinder.gltf") or, for a name with a
// folder ("Fox/Fox.glb"), a shared sample model; and GoogleTest's name for a test of one.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <string>

namespace dqskin::testing_support {

inline std::filesystem::path model_path(const std::string& name) {
  return name.find('/') == std::string::npos ? std::filesystem::path(DQSKIN_TESTDATA_DIR) / name
                                             : std::filesystem::path(DQSKIN_SHARED_TESTDATA_DIR) / name;
}

// The file name without extension, anything but letters and digits as '_' ("Fox/Fox.glb" → "Fox"), for
// INSTANTIATE_TEST_SUITE_P over model names.
inline std::string model_test_name(const testing::TestParamInfo<const char*>& model) {
  std::string name = std::filesystem::path(model.param).stem().string();
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

}  // namespace dqskin::testing_support
