// Measuring one input over its clips (internal to lib/report): the three blends deformed a chunk of frames
// at a time on the CPU reference (never a whole clip at once), each chunk measured in parallel over its
// frames and dropped; then each joint's summary and verdict, and the asset's.
#pragma once

#include "report_data.hpp"

#include "../job/job_plan.hpp"

namespace dqskin::report_detail {

// Throws InputError for an input without skinned meshes, JobCancelled when options.cancel is set.
// `progress` counts the frames measured. The result's JointData point into result.regions.
InputData measure_input(const InputPlan& input, const ReportOptions& options, ProgressCounter& progress);

}  // namespace dqskin::report_detail
