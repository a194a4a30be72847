#include "report_json.hpp"
#include "cross_section.hpp"
#include "verdict.hpp"

#include "dqskin/version.hpp"

#include <cmath>
#include <memory>

namespace dqskin::report_detail {
namespace {

// A figure, or null where it does not exist (JSON has no NaN).
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json verdict_json(const Verdict& v) {
  nlohmann::json out = {{"code", v.code}, {"text", v.text}};
  out["joints"] = v.joints;
  return out;
}

template <class Get>
nlohmann::json series(const std::vector<JointFrame>& frames, Get get) {
  nlohmann::json out = nlohmann::json::array();
  for (const JointFrame& f : frames) out.push_back(number(double(get(f))));
  return out;
}

nlohmann::json flips_series(const std::vector<JointFrame>& frames) {
  nlohmann::json out = nlohmann::json::array();
  for (const JointFrame& f : frames) out.push_back(f.flips);
  return out;
}

}  // namespace

nlohmann::json report_json(const InputData& input, const ReportOptions& options) {
  const ReportThresholds& t = options.thresholds;
  nlohmann::json doc;
  doc["dqskin_report"] = 1;
  std::string tool = "dqskin ";
  tool += kVersion;
  doc["tool"] = tool;
  doc["input"] = {{"file", input.file},
                  {"sha256", input.sha256},
                  {"vertices", input.vertices},
                  {"skinned_vertices", input.skinned_vertices},
                  {"skins", input.skins},
                  {"max_influences", input.max_influences}};
  doc["diagonal"] = number(input.diagonal);
  doc["settings"] = {{"fps", options.plan.frames.fps},
                     {"tolerance", t.tolerance_relative ? t.tolerance : t.tolerance / std::max(input.diagonal, 1e-300)},
                     {"tolerance_length", tolerance_length(t, input.diagonal)},
                     {"tolerance_relative", t.tolerance_relative},
                     {"twist_degrees", t.twist_degrees},
                     {"candy_wrapper", t.candy_wrapper},
                     {"dqs_bulge", t.dqs_bulge},
                     {"zone_weight", kZoneWeight},
                     {"slices", kSlices},
                     {"deformers", {{"lbs", options.fast_cpu ? "fast-cpu" : "cpu-reference"},
                                    {"dqs", options.fast_cpu ? "fast-cpu" : "cpu-reference"},
                                    {"dib", "cpu-reference"}}},
                     {"volume_scope", "per skinned instance: the closed ones, summed"}};
  doc["verdict"] = verdict_json(input.verdict);

  nlohmann::json clips = nlohmann::json::array();
  nlohmann::json images = nlohmann::json::array();
  for (const ClipData& c : input.clips) {
    nlohmann::json clip = {{"name", c.name}, {"frames", c.times.size()}, {"fps", c.fps}, {"times", c.times}};
    if (c.volume) {
      nlohmann::json lbs = nlohmann::json::array(), dqs = nlohmann::json::array(), dib = nlohmann::json::array();
      for (double x : c.volume->lbs) lbs.push_back(number(x));
      for (double x : c.volume->dqs) dqs.push_back(number(x));
      for (double x : c.volume->dib) dib.push_back(number(x));
      clip["volume"] = {{"rest", number(c.volume->rest)}, {"lbs", lbs}, {"dqs", dqs}, {"dib", dib}};
    } else {
      clip["volume"] = nullptr;
    }
    clip["worst_frame"] = c.worst_frame();
    clip["image"] = c.image ? nlohmann::json(c.image->file) : nlohmann::json(nullptr);
    clips.push_back(clip);
    if (c.image)
      images.push_back({{"file", c.image->file},
                        {"clip", c.name},
                        {"frames", c.image->frames},
                        {"caption", "lbs vs dqs distance at the " + std::to_string(c.image->frames.size()) + " worst frames"},
                        {"scale", number(c.image->scale)}});
  }
  doc["clips"] = clips;

  nlohmann::json joints = nlohmann::json::array();
  for (const JointData& j : input.joints) {
    const JointRegion& r = *j.region;
    const JointSummary& s = j.summary;
    nlohmann::json joint = {{"skin", r.skin},
                            {"joint", r.joint},
                            {"node", r.node},
                            {"name", r.name},
                            {"parent", j.parent_name.empty() ? nlohmann::json(nullptr) : nlohmann::json(j.parent_name)},
                            {"vertices", r.vertices.size()},
                            {"zone_vertices", r.zone.size()}};
    joint["summary"] = {{"lbs_dib_max", number(s.lbs_dib_max)},
                        {"dqs_dib_max", number(s.dqs_dib_max)},
                        {"lbs_dqs_max", number(s.lbs_dqs_max)},
                        {"candy_wrapper", number(s.candy_wrapper)},
                        {"dqs_bulge", number(s.dqs_bulge)},
                        {"area_lbs_min", number(s.area_lbs_min)},
                        {"area_dqs_min", number(s.area_dqs_min)},
                        {"twist_max", number(s.twist_max)},
                        {"bend_max", number(s.bend_max)},
                        {"flips", s.flips},
                        {"worst", {{"clip", input.clips.empty() ? "" : input.clips[s.worst_clip].name}, {"clip_index", s.worst_clip},
                                   {"frame", s.worst_frame}}}};
    joint["verdict"] = {{"code", j.verdict.code}, {"text", j.verdict.text}};
    nlohmann::json per_clip = nlohmann::json::array();
    for (size_t c = 0; c < j.clips.size(); ++c) {
      const std::vector<JointFrame>& f = j.clips[c];
      per_clip.push_back({{"clip", input.clips[c].name},
                          {"series",
                           {{"lbs_dib_max", series(f, [](const JointFrame& m) { return m.lbs_dib_max; })},
                            {"lbs_dib_mean", series(f, [](const JointFrame& m) { return m.lbs_dib_mean; })},
                            {"dqs_dib_max", series(f, [](const JointFrame& m) { return m.dqs_dib_max; })},
                            {"dqs_dib_mean", series(f, [](const JointFrame& m) { return m.dqs_dib_mean; })},
                            {"lbs_dqs_max", series(f, [](const JointFrame& m) { return m.lbs_dqs_max; })},
                            {"area_lbs", series(f, [](const JointFrame& m) { return m.area_lbs; })},
                            {"area_dqs", series(f, [](const JointFrame& m) { return m.area_dqs; })},
                            {"area_dib", series(f, [](const JointFrame& m) { return m.area_dib; })},
                            {"area_lbs_over_dib", series(f, [](const JointFrame& m) { return m.lbs_over_dib; })},
                            {"area_dqs_over_dib", series(f, [](const JointFrame& m) { return m.dqs_over_dib; })},
                            {"twist", series(f, [](const JointFrame& m) { return m.twist; })},
                            {"bend", series(f, [](const JointFrame& m) { return m.bend; })},
                            {"flips", flips_series(f)}}}});
    }
    joint["clips"] = per_clip;
    joints.push_back(joint);
  }
  doc["joints"] = joints;
  doc["images"] = images;
  return doc;
}

namespace {

// nlohmann's serializer writes to an output adapter: this one fills a buffer and hands it to the file.
class FileAdapter final : public nlohmann::detail::output_adapter_protocol<char> {
public:
  explicit FileAdapter(AtomicFile& file) : file_(file) { buffer_.reserve(kBuffer); }
  ~FileAdapter() override = default;
  void write_character(char c) override {
    buffer_.push_back(c);
    if (buffer_.size() >= kBuffer) flush();
  }
  void write_characters(const char* s, std::size_t length) override {
    buffer_.append(s, length);
    if (buffer_.size() >= kBuffer) flush();
  }
  void flush() {
    file_.write(buffer_);
    buffer_.clear();
  }

private:
  static constexpr size_t kBuffer = size_t(1) << 16;
  AtomicFile& file_;
  std::string buffer_;
};

}  // namespace

void write_report_json(const nlohmann::json& report, AtomicFile& file) {
  // As json::dump(2, ' ', false, replace) does it, to a file instead of a string. Replace, not throw: the
  // input's file name may be any bytes (as in the manifest).
  const auto adapter = std::make_shared<FileAdapter>(file);
  nlohmann::detail::serializer<nlohmann::json> serializer(adapter, ' ', nlohmann::json::error_handler_t::replace);
  serializer.dump(report, true, false, 2);
  adapter->write_character('\n');
  adapter->flush();
}

}  // namespace dqskin::report_detail
