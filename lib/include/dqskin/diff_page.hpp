// The HTML page of `dqskin diff --html DIR`: one page to look at instead of a log. Every pair, failing
// first and then by error; per pair the reference, the candidate and the difference side by side, a toggle
// and a swipe between reference and candidate, the figures and the thresholds that judged it, and links
// between pairs. Static and self-contained: DIR/index.html and the pictures diff_images wrote under
// DIR/images (DiffOptions::page_dir), an inline style sheet and a few lines of inline script, nothing from
// the network; it works from file://. A geometric diff (two glTF files, two bakes) has the same kind of
// page over its clips or files.
#pragma once

#include "dqskin/geometry_diff.hpp"
#include "dqskin/image_diff.hpp"

#include <string>

namespace dqskin {

// The page of `report`, whose pairs were compared with DiffOptions::page_dir set to the page's folder.
// The same report gives the same bytes (no time stamps).
std::string diff_page_html(const DiffReport& report);

// The page of a geometric diff, made with GeometryDiffOptions::page_dir set to the page's folder: every
// clip (of bakes: every file), failing first and then by its error relative to its size; per clip its
// figures and thresholds, A and B at the worst frame each shaded by its distance to the other with a toggle
// and a swipe between them, the error over the clip's frames as an inline SVG chart with the thresholds,
// and its worst joints; the files, the correspondence and the animation findings at the top.
std::string geometry_page_html(const GeometryDiffReport& report);

}  // namespace dqskin
