// report.json (internal to lib/report): what one input's report holds, in the version-1 layout that the
// HTML page reads (docs/commands/report.md, "report.json").
#pragma once

#include "report_data.hpp"

#include "dqskin/atomic_file.hpp"

#include <nlohmann/json.hpp>

namespace dqskin::report_detail {

nlohmann::json report_json(const InputData& input, const ReportOptions& options);

// report.json's bytes, written to `file` as they are made, never whole in memory (a long clip's series run
// to hundreds of megabytes of text): two-space indentation and a final newline, so that equal reports are
// equal files. Throws OutputError.
void write_report_json(const nlohmann::json& report, AtomicFile& file);

}  // namespace dqskin::report_detail
