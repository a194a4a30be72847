// The reports of a geometric `dqskin diff` (text, JSON, JUnit XML), as dqskin/diff_report.hpp's are for
// images: formatting only. Lengths are in scene units (glTF's meters): the text prints them with an SI
// prefix ("3.1 mm"), JSON and JUnit as plain numbers in scene units. None holds a time of the run, so the
// same inputs give the same bytes (the command prints timings with --verbose, on stderr).
#pragma once

#include "dqskin/geometry_diff.hpp"

#include <string>

namespace dqskin {

// A header line (files, vertices, mode, deformer, correspondence), one line per clip,
// "STATUS  clip NAME, t = T s, max E at JOINT (R of the diagonal D); p99 …, mean …, normals … deg; reason",
// an indented line of its worst joints and its heat map, the findings ("notes:"), and a summary line.
std::string geometry_text(const GeometryDiffReport& report);

// One JSON document: {"a", "b", "mode", "deformer", "thresholds", "correspondence", "vertices", "findings",
// "clips": [{name, status, reason, diagonal, max_error, max_error_relative, worst_time, worst_joint, …,
// joints, frames}], "contact_sheet", "status"}.
std::string geometry_json(const GeometryDiffReport& report);

// JUnit XML: one testcase per clip (classname "dqskin.diff.geometry") and one per failing or warning
// finding; notes in the suite's <system-out>.
std::string geometry_junit(const GeometryDiffReport& report);

}  // namespace dqskin
