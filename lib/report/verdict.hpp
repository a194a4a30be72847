// The verdicts of `dqskin report` (internal to lib/report; docs/commands/report.md, "Verdicts"): per
// joint, which blend it needs and why, in words with the figures that decided; per asset, the joints to
// look at.
#pragma once

#include "report_data.hpp"

namespace dqskin::report_detail {

// The tolerance in scene units: thresholds.tolerance times the diagonal when it is relative.
double tolerance_length(const ReportThresholds& thresholds, double diagonal);

Verdict joint_verdict(const JointData& joint, const std::vector<ClipData>& clips, const ReportThresholds& thresholds,
                      double diagonal);

// From the joints' verdicts: the most pressing code any joint has (use-dqs, add-twist-joints, dqs-bulges,
// dqs-closer, lbs-fine, in that order), naming the joints that have it, with the text of the one where
// lbs strays most, and the other codes' counts.
Verdict asset_verdict(const std::vector<JointData>& joints);

}  // namespace dqskin::report_detail
