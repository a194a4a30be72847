// Measuring one frame of a clip for every joint region (internal to lib/report; docs/commands/report.md):
// the three blends' positions compared vertex by vertex, the cross-section of each blend zone, the
// joint's twist and bend, and the antipodal flips DLB makes. Frames are independent, so a chunk of them
// is measured in parallel, each into its own FrameMeasure.
#pragma once

#include "cross_section.hpp"
#include "skin_regions.hpp"

#include "dqskin/frame_view.hpp"
#include "dqskin/skinning.hpp"

#include <limits>
#include <vector>

namespace dqskin::report_detail {

// NaN stands for "undefined" here; report.json writes it as null.
constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

struct JointFrame {
  double lbs_dib_max = 0, lbs_dib_mean = 0, dqs_dib_max = 0, dqs_dib_mean = 0, lbs_dqs_max = 0;
  // Cross-section: per blend, the smallest ratio of a slice's spread to the same slice's at the rest pose;
  // and, slice by slice against dib, the smallest lbs / dib and the largest dqs / dib.
  double area_lbs = kUndefined, area_dqs = kUndefined, area_dib = kUndefined;
  double lbs_over_dib = kUndefined, dqs_over_dib = kUndefined;
  double twist = kUndefined, bend = kUndefined;  // degrees
  size_t flips = 0;
};

// The three blends' positions at one frame and every used skin's joint transforms (indexed by skin;
// unused skins empty).
struct FrameInput {
  const FrameView* lbs = nullptr;
  const FrameView* dqs = nullptr;
  const FrameView* dib = nullptr;
  const std::vector<JointTransforms>* joints = nullptr;
};

class JointMetrics {
public:
  // `rest`: the dib positions and joint transforms at the rest pose, the reference of the area ratios.
  JointMetrics(const Asset& asset, const SkinRegions& regions, const FrameView& rest,
               const std::vector<JointTransforms>& rest_joints);

  // One JointFrame per region of `regions`, in its order.
  std::vector<JointFrame> measure(const FrameInput& frame) const;

  // The joint transforms of every skin `regions` uses, at `pose`.
  static std::vector<JointTransforms> skin_transforms(const Asset& asset, const SkinRegions& regions, const Pose& pose);

private:
  struct Section {
    std::vector<std::vector<size_t>> slices;  // indices into the region's zone
    std::vector<double> rest;                 // each slice's spread at the rest pose
  };
  // The spread of each slice of region r in `positions`, around the axis the transforms give.
  std::vector<Spread> spreads(size_t r, const FrameView& positions, const JointTransforms& joints) const;

  const SkinRegions& regions_;
  std::vector<Section> sections_;  // per region; no slices without a blend zone
  // Per region, per vertex: the other joints it is blended from (non-zero weight), flat, with offsets.
  std::vector<std::vector<int>> influences_;
  std::vector<std::vector<uint32_t>> influence_start_;
};

}  // namespace dqskin::report_detail
