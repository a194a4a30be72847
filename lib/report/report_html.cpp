// The HTML page of `dqskin report` (report_html.hpp): header, joint table, clips, joints over time.
#include "report_html.hpp"
#include "report_numbers.hpp"
#include "report_style.hpp"
#include "svg_chart.hpp"
#include "../base/base64.hpp"
#include "../base/xml_escape.hpp"

#include <algorithm>
#include <optional>

namespace dqskin::report_detail {
namespace {

using nlohmann::json;

constexpr const char* kAbsent = "\xE2\x80\x93";  // en dash: the figure does not exist (JSON null)

std::string text(const std::string& s) { return io::xml(s, false); }
std::string attribute(const std::string& s) { return io::xml(s, true); }

// Tolerant reading of the document: a missing member, or one of another type, reads as null, an empty
// string or an empty array, so that a damaged report makes a page with gaps, not an exception.
const json& member(const json& object, const char* key) {
  static const json null;
  if (!object.is_object()) return null;
  const auto it = object.find(key);
  return it == object.end() ? null : *it;
}
const json& array_member(const json& object, const char* key) {
  static const json empty = json::array();
  const json& value = member(object, key);
  return value.is_array() ? value : empty;
}
std::string string_of(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number() || value.is_boolean()) return value.dump();
  return "";
}
std::optional<double> number_of(const json& value) {
  if (!value.is_number()) return std::nullopt;
  return value.get<double>();
}
std::string shown(const json& value) {
  const std::optional<double> v = number_of(value);
  return v ? shown_number(*v) : kAbsent;
}
std::vector<std::optional<double>> series_of(const json& value) {
  std::vector<std::optional<double>> out;
  if (value.is_array())
    for (const json& v : value) out.push_back(number_of(v));
  return out;
}
std::vector<double> times_of(const json& clip, size_t frames) {
  std::vector<double> out;
  for (const json& t : array_member(clip, "times")) out.push_back(number_of(t).value_or(0.0));
  // Without times (a damaged document), frame numbers stand in for seconds.
  if (out.empty())
    for (size_t i = 0; i < frames; ++i) out.push_back(double(i));
  return out;
}

// "v-<code>" for the verdict codes the page has colours for.
std::string verdict_class(const std::string& code) {
  for (const char* known : {"lbs-fine", "use-dqs", "add-twist-joints", "dqs-bulges", "dqs-closer"})
    if (code == known) return "v-" + code;
  return "v-other";
}
std::string badge(const json& verdict) {
  const std::string code = string_of(member(verdict, "code"));
  std::string s = "<span class=\"badge ";
  s += verdict_class(code) + "\">" + text(code.empty() ? "no verdict" : code) + "</span>";
  return s;
}

const EmbeddedImage* find_image(const std::vector<EmbeddedImage>& images, const std::string& file) {
  for (const EmbeddedImage& image : images)
    if (image.file == file) return &image;
  return nullptr;
}

// width="…" height="…" from a PNG's IHDR chunk (PNG spec 11.2.2), so that the page lays out before the image
// decodes; nothing for bytes that are not a PNG.
std::string png_size_attributes(const std::vector<uint8_t>& png) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (png.size() < 24 || !std::equal(kSignature, kSignature + 8, png.begin()) || png[12] != 'I' || png[13] != 'H' ||
      png[14] != 'D' || png[15] != 'R')
    return "";
  const auto be32 = [&](size_t at) {
    return uint32_t(png[at]) << 24 | uint32_t(png[at + 1]) << 16 | uint32_t(png[at + 2]) << 8 | uint32_t(png[at + 3]);
  };
  std::string s = " width=\"";
  s += std::to_string(be32(16)) + "\" height=\"" + std::to_string(be32(20)) + "\"";
  return s;
}

// The joints' anchors: by position in "joints", which is unique whatever the names are.
std::string joint_anchor(size_t index) {
  std::string s = "joint-";
  s += std::to_string(index);
  return s;
}
std::string joint_key(const json& joint) {
  return string_of(member(joint, "skin")) + ":" + string_of(member(joint, "joint"));
}
bool is_fine(const json& joint) { return string_of(member(member(joint, "verdict"), "code")) == "lbs-fine"; }

// A chart over a clip's times, its worst frame marked. (Strings are moved in, not assigned from literals:
// GCC 12 warns falsely (-Wrestrict) about assigning some short literals.)
ChartSpec chart(std::string title, std::string unit, const std::vector<double>& times, std::optional<double> worst,
                std::vector<ChartLine> lines) {
  ChartSpec spec;
  spec.title = std::move(title);
  spec.y_unit = std::move(unit);
  spec.x = times;
  spec.marker_x = worst;
  spec.marker_label = std::string("worst");
  spec.lines = std::move(lines);
  return spec;
}

// ----- header ----------------------------------------------------------------------------------------------

std::string fact(const std::string& name, const std::string& value_html) {
  std::string s = "<div><dt>";
  s += text(name) + "</dt><dd>" + value_html + "</dd></div>";
  return s;
}

std::string header(const json& report) {
  const json& input = member(report, "input");
  const std::string file = string_of(member(input, "file"));
  std::string s = "<header>\n<h1>dqskin report: ";
  s += text(file.empty() ? "(unnamed input)" : file) + "</h1>\n<dl class=\"facts\">";
  s += fact("tool", text(string_of(member(report, "tool"))));
  const std::string sha = string_of(member(input, "sha256"));
  if (!sha.empty())
    s += fact("sha256", "<span title=\"" + attribute(sha) + "\">" + text(sha.substr(0, 12)) + "\xE2\x80\xA6</span>");
  s += fact("vertices", shown(member(input, "vertices")) + " (" + shown(member(input, "skinned_vertices")) + " skinned)");
  s += fact("skins", shown(member(input, "skins")));
  s += fact("diagonal", shown(member(report, "diagonal")) + " m");
  s += fact("clips", std::to_string(array_member(report, "clips").size()));
  s += fact("joints", std::to_string(array_member(report, "joints").size()));
  s += "</dl>\n";

  // The asset's verdict, with links to the joints it names.
  const json& verdict = member(report, "verdict");
  s += "<div class=\"card verdict " + verdict_class(string_of(member(verdict, "code"))) + "\">" + badge(verdict) +
       "<strong>" + text(string_of(member(verdict, "text"))) + "</strong>";
  const json& named = array_member(verdict, "joints");
  if (!named.empty()) {
    s += "<p>Joints: ";
    const json& joints = array_member(report, "joints");
    bool first = true;
    for (const json& name : named) {
      const std::string n = string_of(name);
      if (!first) s += ", ";
      first = false;
      size_t index = joints.size();
      for (size_t j = 0; j < joints.size(); ++j)
        if (string_of(member(joints[j], "name")) == n) {
          index = j;
          break;
        }
      s += index < joints.size() ? "<a href=\"#" + joint_anchor(index) + "\">" + text(n) + "</a>" : text(n);
    }
    s += "</p>";
  }
  s += "</div>\n";

  s += "<ul class=\"methods\">"
       "<li><span class=\"swatch lbs\"></span><b>lbs</b> linear blend skinning</li>"
       "<li><span class=\"swatch dqs\"></span><b>dqs</b> dual-quaternion skinning (linear blending, DLB)</li>"
       "<li><span class=\"swatch dib\"></span><b>dib</b> dual-quaternion iterative blending, the exact reference</li>"
       "</ul>\n";
  const json& settings = member(report, "settings");
  if (settings.is_object() && !settings.empty()) {
    s += "<details class=\"settings\"><summary>Settings the verdicts used</summary><dl>";
    for (const auto& [key, value] : settings.items())
      s += "<dt>" + text(key) + "</dt><dd>" + (value.is_number() ? shown(value) : text(value.is_string() ? value.get<std::string>() : value.dump())) + "</dd>";
    s += "</dl></details>\n";
  }
  s += "</header>\n";
  return s;
}

// ----- the joint table ---------------------------------------------------------------------------------------

struct Column {
  const char* key;      // data-key: the member of the joint's "summary" (of the joint itself for vertices)
  const char* heading;
  const char* unit;
  const char* meaning;  // the heading's tooltip
};
constexpr Column kColumns[] = {
    {"vertices", "vertices", "", "region size: vertices whose largest weight is this joint"},
    {"lbs_dib_max", "lbs\xE2\x80\x93" "dib max", "m", "largest distance between lbs and the dib reference, any clip and frame"},
    {nullptr, "% diag", "", "lbs\xE2\x80\x93" "dib max as a percentage of the rest-pose bounding-box diagonal"},
    {"dqs_dib_max", "dqs\xE2\x80\x93" "dib max", "m", "largest distance between dqs and the dib reference"},
    {"candy_wrapper", "candy-wrapper", "0\xE2\x80\x93" "1", "1 \xE2\x88\x92 the smallest lbs/dib cross-section area ratio"},
    {"dqs_bulge", "dqs bulge", "ratio", "largest dqs/dib cross-section area ratio \xE2\x88\x92 1"},
    {"twist_max", "twist max", "\xC2\xB0", "largest twist about the bone, relative to the parent joint"},
    {"bend_max", "bend max", "\xC2\xB0", "largest bend relative to the parent joint"},
    {"flips", "flips", "", "antipodal flips, all frames"},
};

std::string numeric_cell(const char* key, const json& value) {
  std::string s = "<td class=\"num";
  if (!number_of(value)) {
    s += " none\" data-key=\"";
    s += key;
    s += "\" data-value=\"\">";
    s += kAbsent;
    return s + "</td>";
  }
  s += "\" data-key=\"";
  s += key;
  s += "\" data-value=\"" + value.dump() + "\">" + shown(value) + "</td>";
  return s;
}

std::string joint_table(const json& report) {
  const std::optional<double> diagonal = number_of(member(report, "diagonal"));
  std::string s = "<section id=\"summary\">\n<h2>Joints</h2>\n<div class=\"table-wrap\"><table class=\"joints\">\n<thead><tr><th>joint</th>";
  for (const Column& c : kColumns) {
    s += "<th title=\"" + attribute(c.meaning) + "\">" + text(c.heading);
    if (*c.unit) s += " <span class=\"unit\">(" + text(c.unit) + ")</span>";
    s += "</th>";
  }
  s += "<th>verdict</th></tr></thead>\n<tbody>\n";
  const json& joints = array_member(report, "joints");
  for (size_t j = 0; j < joints.size(); ++j) {
    const json& joint = joints[j];
    const json& summary = member(joint, "summary");
    const json& verdict = member(joint, "verdict");
    s += "<tr data-joint=\"" + attribute(joint_key(joint)) + "\"" + (is_fine(joint) ? "" : " class=\"flagged\"") + ">";
    s += "<td class=\"name\"><a href=\"#" + joint_anchor(j) + "\">" + text(string_of(member(joint, "name"))) + "</a>";
    const std::string parent = string_of(member(joint, "parent"));
    s += "<span class=\"parent\">" + (parent.empty() ? std::string("root") : "child of " + text(parent)) + "</span></td>";
    for (const Column& c : kColumns) {
      if (!c.key) {  // % of the diagonal, derived: no data-key, the check compares JSON members only
        const std::optional<double> v = number_of(member(summary, "lbs_dib_max"));
        s += "<td class=\"num pct\">" +
             (v && diagonal && *diagonal > 0 ? shown_number(100 * *v / *diagonal) + " %" : std::string(kAbsent)) + "</td>";
        continue;
      }
      const std::string key = c.key;
      s += numeric_cell(c.key, key == "vertices" ? member(joint, "vertices") : member(summary, c.key));
    }
    s += "<td class=\"verdict-text " + verdict_class(string_of(member(verdict, "code"))) + "\">" + badge(verdict) +
         text(string_of(member(verdict, "text"))) + "</td></tr>\n";
  }
  s += "</tbody></table></div>\n</section>\n";
  return s;
}

// ----- clips ------------------------------------------------------------------------------------------------

std::optional<double> time_of_frame(const std::vector<double>& times, const json& frame) {
  const std::optional<double> f = number_of(frame);
  if (!f || *f < 0 || *f >= double(times.size())) return std::nullopt;
  return times[size_t(*f)];
}

std::string image_figure(const json& report, const std::vector<double>& times, const std::string& file,
                         const std::vector<EmbeddedImage>& images) {
  const json* meta = nullptr;
  for (const json& entry : array_member(report, "images"))
    if (string_of(member(entry, "file")) == file) {
      meta = &entry;
      break;
    }
  static const json null;
  const json& info = meta ? *meta : null;
  const std::string caption = string_of(member(info, "caption"));
  std::string s = "<figure class=\"sheet\">";
  if (const EmbeddedImage* image = find_image(images, file)) {
    s += "<img src=\"data:image/png;base64," + io::base64(image->png) + "\" data-file=\"" + attribute(file) + "\" alt=\"" +
         attribute(caption.empty() ? file : caption) + "\"" + png_size_attributes(image->png) + ">";
  } else {
    s += "<p class=\"missing\">" + text(file) + ": not embedded in this page</p>";
  }
  s += "<figcaption><b>" + text(file) + "</b>";
  if (!caption.empty()) s += ": " + text(caption);
  const json& frames = array_member(info, "frames");
  if (!frames.empty()) {
    s += ". Frames ";
    for (size_t i = 0; i < frames.size(); ++i) {
      if (i) s += ", ";
      s += shown(frames[i]);
      if (const std::optional<double> t = time_of_frame(times, frames[i])) s += " (" + shown_number(*t) + " s)";
    }
  }
  s += ".";
  if (const std::optional<double> scale = number_of(member(info, "scale"))) {
    s += "<span class=\"scale\">0 <span class=\"bar\"></span> " + shown_number(*scale) +
         " m <span class=\"note\">(distance, the render's heat colours)</span></span>";
  }
  s += "</figcaption></figure>\n";
  return s;
}

void clip_sections(const json& report, const std::vector<EmbeddedImage>& images, const HtmlSink& out) {
  const json& clips = array_member(report, "clips");
  if (clips.empty()) return;
  out("<section id=\"clips\">\n<h2>Clips</h2>\n");
  for (size_t c = 0; c < clips.size(); ++c) {
    std::string s;
    const json& clip = clips[c];
    const std::string name = string_of(member(clip, "name"));
    const size_t frames = size_t(std::max(0.0, number_of(member(clip, "frames")).value_or(0.0)));
    const std::vector<double> times = times_of(clip, frames);
    const std::optional<double> worst_time = time_of_frame(times, member(clip, "worst_frame"));
    s += "<div class=\"card clip\" id=\"clip-" + std::to_string(c) + "\">\n<h3>" + text(name) + "<span class=\"meta\">" +
         shown(member(clip, "frames")) + " frames at " + shown(member(clip, "fps")) + " fps";
    if (!times.empty()) s += ", " + shown_number(times.back()) + " s";
    if (worst_time) s += "; largest lbs\xE2\x80\x93" "dib displacement at frame " + shown(member(clip, "worst_frame")) + " (" + shown_number(*worst_time) + " s)";
    s += "</span></h3>\n<div class=\"clip-body\">\n";

    const json& volume = member(clip, "volume");
    if (volume.is_object()) {
      ChartSpec spec = chart("Volume relative to rest", "ratio", times, worst_time,
                             {{"lbs", "lbs", series_of(member(volume, "lbs"))},
                              {"dqs", "dqs", series_of(member(volume, "dqs"))},
                              {"dib", "dib", series_of(member(volume, "dib"))}});
      spec.reference_y = 1.0;
      s += "<figure class=\"volume\">" + line_chart_svg(spec) + "<figcaption>rest volume " + shown(member(volume, "rest")) +
           " m\xC2\xB3</figcaption></figure>\n";
    } else {
      s += "<p class=\"note\">No volume: the deformed meshes are not closed.</p>\n";
    }

    // The clip's contact sheet, and any other image of "images" for this clip, each once.
    // Clip names may repeat (glTF does not forbid it), so an entry of "images" found by name is taken only
    // when it is no clip's own "image": each clip's sheet is shown under that clip alone.
    std::vector<std::string> files;
    if (member(clip, "image").is_string()) files.push_back(member(clip, "image").get<std::string>());
    for (const json& entry : array_member(report, "images"))
      if (string_of(member(entry, "clip")) == name) {
        const std::string file = string_of(member(entry, "file"));
        const bool another_clips = std::any_of(clips.begin(), clips.end(), [&](const json& other) {
          return member(other, "image").is_string() && member(other, "image").get<std::string>() == file;
        });
        if (!file.empty() && !another_clips && std::find(files.begin(), files.end(), file) == files.end())
          files.push_back(file);
      }
    for (const std::string& file : files) s += image_figure(report, times, file, images);
    s += "</div>\n</div>\n";
    out(s);
  }
  out("</section>\n");
}

// ----- joints over time -------------------------------------------------------------------------------------

std::string joint_article(const json& report, const json& joint, size_t index) {
  const json& verdict = member(joint, "verdict");
  const json& worst = member(member(joint, "summary"), "worst");
  std::string s = "<article class=\"card joint " + verdict_class(string_of(member(verdict, "code"))) + "\" id=\"" +
                  joint_anchor(index) + "\">\n<h3>" + text(string_of(member(joint, "name"))) + "<span class=\"meta\">skin " +
                  shown(member(joint, "skin")) + ", joint " + shown(member(joint, "joint")) + ", " + shown(member(joint, "vertices")) +
                  " vertices</span></h3>\n<p>" + badge(verdict) + text(string_of(member(verdict, "text"))) + "</p>\n";
  const json& clips = array_member(report, "clips");
  const json& joint_clips = array_member(joint, "clips");
  for (size_t c = 0; c < joint_clips.size(); ++c) {
    const json& entry = joint_clips[c];
    const std::string clip_name = string_of(member(entry, "clip"));
    // A joint's clips are the report's, in its order; the name is checked, as clip names may repeat, and
    // searched for only in a document that does not keep the order.
    const json* clip = nullptr;
    if (c < clips.size() && string_of(member(clips[c], "name")) == clip_name) clip = &clips[c];
    for (size_t k = 0; k < clips.size() && !clip; ++k)
      if (string_of(member(clips[k], "name")) == clip_name) clip = &clips[k];
    const json& series = member(entry, "series");
    const std::vector<std::optional<double>> lbs_dib = series_of(member(series, "lbs_dib_max"));
    static const json null;
    const std::vector<double> times = times_of(clip ? *clip : null, lbs_dib.size());
    std::optional<double> marker;
    const std::optional<double> worst_clip = number_of(member(worst, "clip_index"));
    if (worst_clip ? *worst_clip == double(c) : string_of(member(worst, "clip")) == clip_name)
      marker = time_of_frame(times, member(worst, "frame"));

    ChartSpec displacement = chart("Distance to dib, max over the region", "m", times, marker,
                                   {{"lbs", "lbs", lbs_dib}, {"dqs", "dqs", series_of(member(series, "dqs_dib_max"))}});
    displacement.include_zero = true;
    ChartSpec area = chart("Cross-section area relative to rest", "ratio", times, marker,
                           {{"lbs", "lbs", series_of(member(series, "area_lbs"))},
                            {"dqs", "dqs", series_of(member(series, "area_dqs"))},
                            {"dib", "dib", series_of(member(series, "area_dib"))}});
    area.reference_y = 1.0;
    area.empty_text = std::string("no cross-section");
    ChartSpec angles = chart("Joint angles relative to the parent", "\xC2\xB0", times, marker,
                             {{"twist", "twist", series_of(member(series, "twist"))},
                              {"bend", "bend", series_of(member(series, "bend"))}});
    angles.empty_text = std::string("no parent joint");

    s += "<h4>" + text(clip_name) + "</h4>\n<div class=\"charts\">\n" + line_chart_svg(displacement) + "\n" +
         line_chart_svg(area) + "\n" + line_chart_svg(angles) + "\n</div>\n";
  }
  s += "</article>\n";
  return s;
}

void joint_sections(const json& report, const HtmlSink& out) {
  const json& joints = array_member(report, "joints");
  if (joints.empty()) return;
  std::string s = "<section id=\"joints\">\n<h2>Joints over time</h2>\n";
  s += "<p class=\"note\">Per clip and frame: the largest distance of the joint's region to the dib reference, its "
       "cross-section area and its twist and bend. Null figures leave gaps; a dashed red line marks the joint's "
       "worst frame.</p>\n";
  // Joints with something to say first, in the document's order; the rest folded away.
  out(s);
  size_t fine = 0;
  for (size_t j = 0; j < joints.size(); ++j) {
    if (is_fine(joints[j])) ++fine;
    else out(joint_article(report, joints[j], j));
  }
  if (fine > 0) {
    out("<details class=\"fine\"><summary>" + std::to_string(fine) + (fine == 1 ? " joint" : " joints") +
        " where lbs is fine</summary>\n");
    for (size_t j = 0; j < joints.size(); ++j)
      if (is_fine(joints[j])) out(joint_article(report, joints[j], j));
    out("</details>\n");
  }
  out("</section>\n");
}

}  // namespace

void write_report_html(const json& report, const std::vector<EmbeddedImage>& images, const HtmlSink& out) {
  const std::string file = string_of(member(member(report, "input"), "file"));
  std::string s = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                  "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                  // Nothing from anywhere: no script, no fetch, images only as data URIs.
                  "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; style-src 'unsafe-inline'\">\n"
                  "<title>";
  s += text("dqskin report: " + file) + "</title>\n<style>" + kReportStyle + "</style>\n</head>\n<body>\n<main>\n";
  s += header(report);
  s += joint_table(report);
  out(s);
  clip_sections(report, images, out);
  joint_sections(report, out);
  out("<footer>Made by " + text(string_of(member(report, "tool"))) +
      ". Lengths in scene units (glTF: metres), angles in degrees, areas and volumes as ratios to the rest pose; "
      "\xE2\x80\x93 marks a figure that does not exist.</footer>\n</main>\n</body>\n</html>\n");
}

std::string report_html(const json& report, const std::vector<EmbeddedImage>& images) {
  std::string page;
  write_report_html(report, images, [&page](std::string_view piece) { page += piece; });
  return page;
}

}  // namespace dqskin::report_detail
