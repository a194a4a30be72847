// What `dqskin report` measured of one input, gathered before it is judged and written (internal to
// lib/report): per clip its frames and volumes, per joint region its series and summary.
#pragma once

#include "joint_metrics.hpp"
#include "skin_regions.hpp"

#include "dqskin/report.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dqskin::report_detail {

struct ClipVolume {
  double rest = 0;
  std::vector<double> lbs, dqs, dib;  // ratio to rest per frame
};

struct ClipImage {
  std::string file;             // beside report.json
  std::vector<size_t> frames;   // the worst frames, in frame order
  double scale = 0;             // the legend's top colour, scene units
};

struct ClipData {
  std::string name;
  double fps = 0;
  std::vector<double> times;
  std::optional<ClipVolume> volume;
  std::vector<double> worst_lbs_dib;  // per frame: the largest lbs–dib over every region
  double lbs_dqs_max = 0;             // over every region and frame: the contact sheet's scale
  std::optional<ClipImage> image;
  size_t worst_frame() const;         // the frame with the largest worst_lbs_dib (first on ties)
};

struct JointSummary {
  double lbs_dib_max = 0, dqs_dib_max = 0, lbs_dqs_max = 0;
  double candy_wrapper = kUndefined, dqs_bulge = kUndefined;
  double area_lbs_min = kUndefined, area_dqs_min = kUndefined;
  double twist_max = kUndefined, bend_max = kUndefined;
  size_t flips = 0;
  size_t worst_clip = 0, worst_frame = 0;  // where lbs–dib is largest
  size_t twist_clip = 0;                   // where |twist| is largest
};

struct Verdict {
  std::string code, text;
  std::vector<std::string> joints;
};

struct JointData {
  const JointRegion* region = nullptr;
  std::string parent_name;                 // empty without a parent joint
  std::vector<std::vector<JointFrame>> clips;  // per clip, per frame
  JointSummary summary;
  Verdict verdict;
};

struct InputData {
  std::unique_ptr<const SkinRegions> regions;  // what the joints' JointRegion pointers point into
  std::string file, sha256;
  size_t vertices = 0, skinned_vertices = 0, skins = 0;
  int max_influences = 0;
  double diagonal = 0;
  std::vector<ClipData> clips;
  std::vector<JointData> joints;
  Verdict verdict;
};

// The summary of a joint over every clip and frame (docs/commands/report.md, "Summary").
JointSummary summarize(const std::vector<std::vector<JointFrame>>& clips);

}  // namespace dqskin::report_detail
