// `dqskin diff GOLDEN CANDIDATE --approve`: the candidates of failing pairs become the goldens, all of them
// or none, so that an intended change of the renders is accepted with one command and one commit (as
// Filament's update_golden.py does for its render tests). A dry run lists what would change.
#pragma once

#include "dqskin/image_diff.hpp"

#include <string>
#include <vector>

namespace dqskin {

// The approvals of a diff of `report.a` (the goldens) against `report.b`: every failing pair whose
// candidate exists and could be read: a golden that differs, has another size or channel count or cannot
// be read is replaced; a candidate with no golden is added (under report.a by the pair's name when A is a
// folder). Passing and warning pairs, and goldens without a candidate, are left as they are.
std::vector<Approval> approvals(const DiffReport& report);

// Copies every candidate over its golden, byte for byte, all or none: each file is written to a temporary
// beside its golden and renamed, the old goldens kept aside until every one has been written, and put back
// if one cannot be (a read-only folder, a full disk). Throws OutputError naming the file that failed, or
// InputError for a candidate that cannot be read; then nothing has changed.
void approve(const std::vector<Approval>& approvals);

}  // namespace dqskin
