// The HTML page of `dqskin report` (internal to lib/report): one report.json document and its contact
// sheets as a single, static, self-contained HTML5 page: inline style, inline SVG charts, the PNGs as
// data URIs; no script, nothing loaded from anywhere, readable from file://.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace dqskin::report_detail {

// A PNG that the page embeds. `file`: its name beside report.json (the "image" of a clip, the "file" of an
// entry of "images"); `png`: the file's bytes.
struct EmbeddedImage {
  std::string file;
  std::vector<uint8_t> png;
};

// The page for one report.json document (version 1, as `dqskin report` writes it). Every string
// of the document is escaped; numbers are shown by shown_number() (report_numbers.hpp), and every numeric
// cell of the joint table carries the JSON number itself in data-value. Missing members and members of an
// unexpected type are shown as absent ("–"), never a crash. An image named by the document but not in
// `images` is named on the page as missing. Deterministic: the same arguments give the same bytes.
std::string report_html(const nlohmann::json& report, const std::vector<EmbeddedImage>& images);

// Receives the page piece by piece: a section, a clip or a joint at a time.
using HtmlSink = std::function<void(std::string_view)>;

// The same page handed to `out` as it is made, so that it is never whole in memory (a thousand clips'
// sheets and charts made a page of hundreds of MB).
void write_report_html(const nlohmann::json& report, const std::vector<EmbeddedImage>& images, const HtmlSink& out);

}  // namespace dqskin::report_detail
