// report()'s checks of its options, made before any input is read: a report is made whole, so a shard is
// refused, and the output folder the call made is taken back with it.
#include "dqskin/report.hpp"

#include "dqskin/error.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace dqskin {
namespace {

TEST(ReportOptions, AShardIsRefusedAndTheFolderMadeForItIsTakenBack) {
  testing_support::ScratchDir scratch("report_options");
  ReportOptions options;
  options.plan.out_dir = (scratch.path() / "new" / "out").string();
  options.plan.shard = {0, 2};
  EXPECT_THROW(report({std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf"}, options), InputError);
  EXPECT_FALSE(std::filesystem::exists(scratch.path() / "new"));
  options.plan.shard = {};  // the control: the same options unsharded pass the check (and fail on no input)
  const ReportResult result = report({(scratch.path() / "missing.gltf").string()}, options);
  ASSERT_EQ(result.inputs.size(), 1u);
  EXPECT_NE(result.inputs[0].error, "");
  EXPECT_FALSE(std::filesystem::exists(scratch.path() / "new"));  // nothing reported: no folder either
}

}  // namespace
}  // namespace dqskin
