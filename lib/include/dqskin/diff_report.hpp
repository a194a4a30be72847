// The reports of `dqskin diff` (text, JSON, JUnit XML): a DiffReport written for people, scripts and CI.
// Apart from the measuring (dqskin/image_diff.hpp) because they only format its result: a caller that
// compares without reporting, or a new format, touches one side only.
#pragma once

#include "dqskin/image_diff.hpp"

#include <string>

namespace dqskin {

// The reports. Numbers are printed with 6 significant digits (%g) in text and JUnit, shortest round-trip
// in JSON; the same report gives the same bytes.
//
// Text: one line per pair, "STATUS  name  max M at (x, y, C)  mean M  RMS R  PSNR P dB  over warn N (p%)
// over fail N (p%)" or "STATUS  name  problem", with "  heat map FILE" when one was written, then
// "summary: STATUS (N pairs: P pass, W warn, F fail)".
std::string diff_text(const DiffReport& report);

// One JSON document: {"a", "b", "thresholds", "pairs": [...], "summary"}; each pair has name, a, b (null
// when missing), status, and either problem or the metrics, reason and heat_map. Values that are not
// finite (PSNR of identical images, an infinite hard_fail) are null.
std::string diff_json(const DiffReport& report);

// JUnit XML: one testsuite, its thresholds as properties, one testcase per pair (classname "dqskin.diff",
// name the pair's name); a failing pair has a <failure> whose message is the reason and whose text holds
// the files and metrics; a warning is reported in <system-out> (JUnit has no warning state). No times or
// host names, so the same inputs give the same file.
std::string diff_junit(const DiffReport& report);

}  // namespace dqskin
