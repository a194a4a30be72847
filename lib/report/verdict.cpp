#include "verdict.hpp"

#include <array>
#include <cmath>
#include <cstdio>

namespace dqskin::report_detail {
namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

// "0.0123 (1.2 % of the diagonal)"
std::string length(double value, double diagonal) {
  std::string s = format("%.3g", value);
  if (diagonal > 0) {
    s += " (";
    s += format("%.2g", 100.0 * value / diagonal);
    s += " % of the diagonal)";
  }
  return s;
}

}  // namespace

double tolerance_length(const ReportThresholds& thresholds, double diagonal) {
  return thresholds.tolerance_relative ? thresholds.tolerance * diagonal : thresholds.tolerance;
}

Verdict joint_verdict(const JointData& joint, const std::vector<ClipData>& clips, const ReportThresholds& thresholds,
                      double diagonal) {
  const JointSummary& s = joint.summary;
  const std::string& name = joint.region->name;
  const double tolerance = tolerance_length(thresholds, diagonal);
  const std::string lbs_off = "lbs is off by up to " + length(s.lbs_dib_max, diagonal);
  const std::string dqs_off = "dqs by " + length(s.dqs_dib_max, diagonal);
  Verdict v;
  v.joints = {name};
  if (s.lbs_dib_max <= tolerance) {
    v.code = "lbs-fine";
    v.text = "lbs is fine: " + name + " differs from the exact blend by at most " + length(s.lbs_dib_max, diagonal) +
             ", within the tolerance " + length(tolerance, diagonal);
  } else if (!std::isnan(s.twist_max) && s.twist_max >= thresholds.twist_degrees) {
    v.code = "add-twist-joints";
    v.text = "add twist joints: " + name + " twists " + format("%.0f", s.twist_max) + "° in " +
             clips[s.twist_clip].name + " (" + lbs_off + ", " + dqs_off + ")";
  } else if ((!std::isnan(s.candy_wrapper) && s.candy_wrapper >= thresholds.candy_wrapper) || s.dqs_dib_max <= tolerance) {
    v.code = "use-dqs";
    v.text = "use dqs: ";
    if (!std::isnan(s.candy_wrapper) && s.candy_wrapper >= thresholds.candy_wrapper)
      v.text += "lbs collapses the cross-section of " + name + " to " + format("%.0f", 100.0 * (1.0 - s.candy_wrapper)) +
                " % of the exact blend's (candy-wrapper index " + format("%.2f", s.candy_wrapper) + "); ";
    else
      v.text += name + ": ";
    v.text += lbs_off + ", " + dqs_off;
  } else if (!std::isnan(s.dqs_bulge) && s.dqs_bulge >= thresholds.dqs_bulge) {
    v.code = "dqs-bulges";
    v.text = "dqs bulges: the cross-section of " + name + " grows to " + format("%.0f", 100.0 * (1.0 + s.dqs_bulge)) +
             " % of the exact blend's; " + lbs_off + ", " + dqs_off;
  } else {
    v.code = "dqs-closer";
    v.text = (s.dqs_dib_max < s.lbs_dib_max ? "dqs is closer: " : "neither blend is within the tolerance: ") + name + ": " +
             lbs_off + ", " + dqs_off;
  }
  return v;
}

Verdict asset_verdict(const std::vector<JointData>& joints) {
  static const std::array<const char*, 5> order = {"use-dqs", "add-twist-joints", "dqs-bulges", "dqs-closer", "lbs-fine"};
  static const std::array<const char*, 5> words = {"use dqs", "add twist joints", "dqs bulges", "dqs is closer", "lbs is fine"};
  Verdict v;
  std::string others;
  for (size_t k = 0; k < order.size(); ++k) {
    std::vector<std::string> names;
    const JointData* worst = nullptr;  // the one lbs strays most at: its text gives the figures
    for (const JointData& j : joints)
      if (j.verdict.code == order[k]) {
        names.push_back(j.region->name);
        if (!worst || j.summary.lbs_dib_max > worst->summary.lbs_dib_max) worst = &j;
      }
    if (names.empty()) continue;
    if (v.code.empty()) {
      v.code = order[k];
      v.joints = names;
      v.text = words[k];
      v.text += ": ";
      for (size_t i = 0; i < names.size(); ++i) {
        if (i == 3 && names.size() > 4) {
          v.text += " and " + std::to_string(names.size() - 3) + " more";
          break;
        }
        if (i) v.text += i + 1 == names.size() ? " and " : ", ";
        v.text += names[i];
      }
      // The worst joint's figures, without its own "use dqs: "-like opening.
      const std::string& text = worst->verdict.text;
      const size_t colon = text.find(": ");
      v.text += " — ";
      v.text += colon == std::string::npos ? text : text.substr(colon + 2);
    } else {
      others += others.empty() ? "; also " : ", ";
      others += std::to_string(names.size()) + " joint" + (names.size() == 1 ? "" : "s") + " " + order[k];
    }
  }
  if (v.code.empty()) {
    v.code = "lbs-fine";
    v.text = "lbs is fine: no skinned joint to measure";
  }
  v.text += others;
  return v;
}

}  // namespace dqskin::report_detail
