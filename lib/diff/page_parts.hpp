// What the pages of `dqskin diff --html` share (internal to lib/diff): the escaping, the status colours,
// the style sheet and the script of the toggle and the swipe, the compare box they drive and the links
// between sections. diff_page.cpp makes the page of images, geometry_page.cpp that of glTF files and bakes.
#pragma once

#include "dqskin/image_diff.hpp"
#include "../base/xml_escape.hpp"

#include <string>

namespace dqskin::diff_detail {

inline std::string text(const std::string& s) { return io::xml(s, false); }
inline std::string attribute(const std::string& s) { return io::xml(s, true); }

inline std::string status_class(DiffStatus s) { return s == DiffStatus::kFail ? "fail" : s == DiffStatus::kWarn ? "warn" : "pass"; }

inline constexpr const char* kStyle = R"(
:root { color-scheme: dark; --fail: #e5484d; --warn: #f5a524; --pass: #46a758; }
body { margin: 0; font: 14px/1.45 system-ui, sans-serif; background: #111; color: #ddd; }
header, section { padding: 12px 20px; border-bottom: 1px solid #333; }
h1 { font-size: 18px; margin: 0 0 4px; } h2 { font-size: 15px; margin: 0 0 6px; word-break: break-all; }
a { color: #8ab4f8; } table { border-collapse: collapse; } th, td { padding: 2px 10px 2px 0; text-align: left; vertical-align: top; }
th { font-weight: 500; color: #aaa; } td { font-variant-numeric: tabular-nums; word-break: break-all; }
.status { display: inline-block; min-width: 3.2em; padding: 0 6px; border-radius: 3px; color: #111; font-weight: 700; text-align: center; }
.fail .status, .status.fail { background: var(--fail); } .warn .status, .status.warn { background: var(--warn); }
.pass .status, .status.pass { background: var(--pass); }
#index td { padding-right: 16px; }
.views { display: flex; flex-wrap: wrap; gap: 12px; margin-top: 8px; }
figure { margin: 0; } figcaption { color: #aaa; font-size: 12px; margin-bottom: 2px; }
.views img, .stack img { max-width: 420px; max-height: 420px; image-rendering: pixelated; background: #000; display: block; }
.compare { margin-top: 8px; } .compare button { font: inherit; margin-right: 8px; }
.stack { position: relative; display: inline-block; margin-top: 6px; }
.stack img.over { position: absolute; left: 0; top: 0; }
.legend { display: flex; align-items: center; gap: 6px; font-size: 12px; margin-top: 4px; }
.legend .bar { width: 160px; height: 10px; background: linear-gradient(90deg, #440154, #3b528b, #21918c, #5ec962, #fde725); }
.note { color: #888; font-size: 12px; margin: 2px 0; } nav { margin-top: 8px; font-size: 13px; }
)";

// Toggle: the candidate on top, shown or hidden (the reference below it). Swipe: the candidate clipped to
// the right of the slider. Both only change styles; every picture is a file beside the page.
inline constexpr const char* kScript = R"(
for (const box of document.querySelectorAll('.compare')) {
  const over = box.querySelector('img.over'), toggle = box.querySelector('button.toggle'),
        swipe = box.querySelector('input.swipe'), label = box.querySelector('.showing');
  const show = (b) => { over.style.visibility = b ? 'visible' : 'hidden'; label.textContent = b ? 'B (candidate)' : 'A (reference)'; };
  toggle.addEventListener('click', () => { swipe.value = 0; over.style.clipPath = 'inset(0 0 0 0%)'; show(over.style.visibility === 'hidden'); });
  swipe.addEventListener('input', () => { show(true); over.style.clipPath = 'inset(0 0 0 ' + swipe.value + '%)'; label.textContent = 'A left, B right'; });
}
)";

// The toggle and the swipe between A's picture (below) and B's (above), as kScript drives them.
inline std::string compare_box(const std::string& a, const std::string& b) {
  return "<div class=\"compare\"><button class=\"toggle\" type=\"button\">toggle A / B</button>swipe <input class=\"swipe\" "
         "type=\"range\" min=\"0\" max=\"100\" value=\"0\"> showing <span class=\"showing\">B (candidate)</span><br>"
         "<div class=\"stack\"><img class=\"under\" loading=\"lazy\" src=\"" + attribute(a) +
         "\" alt=\"A\"><img class=\"over\" loading=\"lazy\" src=\"" + attribute(b) + "\" alt=\"B\"></div></div>";
}

// The links at the end of section k of n: to the previous section, the index and the next one.
inline std::string section_nav(size_t k, size_t n) {
  std::string h = "<nav>";
  if (k > 0) h += "<a href=\"#p" + std::to_string(k - 1) + "\">\u2190 previous</a> \u00b7 ";
  h += "<a href=\"#index\">index</a>";
  if (k + 1 < n) h += " \u00b7 <a href=\"#p" + std::to_string(k + 1) + "\">next \u2192</a>";
  return h + "</nav>";
}

}  // namespace dqskin::diff_detail
