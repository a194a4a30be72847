#include "report_data.hpp"

#include <algorithm>
#include <cmath>

namespace dqskin::report_detail {

size_t ClipData::worst_frame() const {
  size_t worst = 0;
  for (size_t f = 1; f < worst_lbs_dib.size(); ++f)
    if (worst_lbs_dib[f] > worst_lbs_dib[worst]) worst = f;
  return worst;
}

JointSummary summarize(const std::vector<std::vector<JointFrame>>& clips) {
  JointSummary s;
  double lbs_over_dib_min = kUndefined, dqs_over_dib_max = kUndefined;
  // NaN-aware min and max: an undefined figure never replaces a defined one.
  auto lower = [](double& into, double x) { if (!std::isnan(x) && (std::isnan(into) || x < into)) into = x; };
  auto higher = [](double& into, double x) { if (!std::isnan(x) && (std::isnan(into) || x > into)) into = x; };
  bool first = true;
  for (size_t c = 0; c < clips.size(); ++c)
    for (size_t f = 0; f < clips[c].size(); ++f) {
      const JointFrame& m = clips[c][f];
      if (first || m.lbs_dib_max > s.lbs_dib_max) s.worst_clip = c, s.worst_frame = f;
      first = false;
      s.lbs_dib_max = std::max(s.lbs_dib_max, m.lbs_dib_max);
      s.dqs_dib_max = std::max(s.dqs_dib_max, m.dqs_dib_max);
      s.lbs_dqs_max = std::max(s.lbs_dqs_max, m.lbs_dqs_max);
      lower(lbs_over_dib_min, m.lbs_over_dib);
      higher(dqs_over_dib_max, m.dqs_over_dib);
      lower(s.area_lbs_min, m.area_lbs);
      lower(s.area_dqs_min, m.area_dqs);
      const double twist_before = s.twist_max;
      higher(s.twist_max, std::abs(m.twist));
      if (s.twist_max != twist_before && !std::isnan(s.twist_max)) s.twist_clip = c;
      higher(s.bend_max, m.bend);
      s.flips += m.flips;
    }
  if (!std::isnan(lbs_over_dib_min)) s.candy_wrapper = std::clamp(1.0 - lbs_over_dib_min, 0.0, 1.0);
  if (!std::isnan(dqs_over_dib_max)) s.dqs_bulge = dqs_over_dib_max - 1.0;
  return s;
}

}  // namespace dqskin::report_detail
