// A suite's rules in one place: the preset file of `dqskin diff --preset`, and which rule a pair follows
// (include/dqskin/image_diff.hpp).
#include "dqskin/image_diff.hpp"
#include "diff_numbers.hpp"

#include "dqskin/error.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dqskin {
namespace {

using nlohmann::json;
using diff_detail::number;

// A number of the rule at `where` for `key`, within [low, high].
double number_of(const json& value, const std::string& where, const char* key, double low, double high) {
  if (!value.is_number()) throw InputError(where + ": \"" + key + "\" must be a number");
  const double v = value.get<double>();
  if (!(v >= low && v <= high))
    throw InputError(where + ": \"" + key + "\" must be from " + number(low) + " to " + number(high) + ", not " + number(v));
  return v;
}

}  // namespace

bool glob_match(const std::string& pattern, const std::string& name) {
  // match[i][j]: pattern from i matches name from j. Filled from the ends, so that any number of stars
  // costs |pattern| × |name| steps, never a backtracking search.
  const size_t p = pattern.size(), n = name.size();
  std::vector<uint8_t> match((p + 1) * (n + 1), 0);
  const auto at = [&](size_t i, size_t j) -> uint8_t& { return match[i * (n + 1) + j]; };
  at(p, n) = 1;
  for (size_t i = p; i-- > 0;)
    for (size_t j = n + 1; j-- > 0;) {
      if (pattern[i] == '*') {
        const bool crosses = i + 1 < p && pattern[i + 1] == '*';
        const size_t rest = i + (crosses ? 2 : 1);
        bool m = at(rest, j) || (j < n && (crosses || name[j] != '/') && at(i, j + 1));
        // "**/" also stands for no folder at all: "**/a.png" matches "a.png".
        if (crosses && rest < p && pattern[rest] == '/') m = m || at(rest + 1, j);
        at(i, j) = m;
      } else {
        at(i, j) = j < n && (pattern[i] == '?' ? name[j] != '/' : pattern[i] == name[j]) && at(i + 1, j + 1);
      }
    }
  return at(0, 0);
}

std::vector<DiffRule> read_diff_rules(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the preset file");
  std::stringstream text;
  text << in.rdbuf();
  json doc;
  try {
    doc = json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw InputError(path + ": not JSON: " + e.what());
  }
  if (!doc.is_object() || !doc.contains("rules") || !doc["rules"].is_array())
    throw InputError(path + ": a preset file is an object with an array \"rules\"");
  for (const auto& [key, value] : doc.items())
    if (key != "rules") throw InputError(path + ": unknown key \"" + key + "\" (a preset has \"rules\")");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<DiffRule> rules;
  for (size_t i = 0; i < doc["rules"].size(); ++i) {
    const json& r = doc["rules"][i];
    const std::string where = path + ": rules[" + std::to_string(i) + "]";
    if (!r.is_object()) throw InputError(where + ": a rule is an object");
    if (!r.contains("match") || !r["match"].is_string() || r["match"].get<std::string>().empty())
      throw InputError(where + ": \"match\" (a name pattern) is required");
    DiffRule rule;
    rule.pattern = r["match"].get<std::string>();
    DiffThresholds values;
    std::vector<std::string> given;
    const std::pair<const char*, double DiffThresholds::*> thresholds[] = {
        {"fail", &DiffThresholds::fail},         {"hardfail", &DiffThresholds::hard_fail},
        {"failmean", &DiffThresholds::fail_mean}, {"warn", &DiffThresholds::warn},
        {"hardwarn", &DiffThresholds::hard_warn}, {"warnmean", &DiffThresholds::warn_mean}};
    const std::pair<const char*, double DiffThresholds::*> percents[] = {{"failpercent", &DiffThresholds::fail_percent},
                                                                          {"warnpercent", &DiffThresholds::warn_percent}};
    for (const auto& [key, value] : r.items()) {
      bool known = key == "match";
      for (const auto& [name, member] : thresholds)
        if (key == name) values.*member = number_of(value, where, name, 0, std::numeric_limits<double>::max()), known = true;
      for (const auto& [name, member] : percents)
        if (key == name) values.*member = number_of(value, where, name, 0, 100), known = true;
      if (known && key != "match") given.push_back("--" + key);
      if (key == "metric") {
        if (!value.is_string() || (value != "idiff" && value != "flip"))
          throw InputError(where + ": \"metric\" must be \"idiff\" or \"flip\"");
        rule.metric = value == "flip" ? DiffMetric::kFlip : DiffMetric::kIdiff;
        known = true;
      } else if (key == "ppd") {
        rule.pixels_per_degree = number_of(value, where, "ppd", 1, 1000);
        known = true;
      } else if (key == "mask") {
        if (!value.is_string() || value.get<std::string>().empty()) throw InputError(where + ": \"mask\" must be an image file name");
        rule.mask.images.push_back((folder / value.get<std::string>()).string());
        known = true;
      } else if (key == "ignore") {
        if (!value.is_array()) throw InputError(where + ": \"ignore\" must be an array of [x, y, width, height]");
        for (const json& rect : value) {
          if (!rect.is_array() || rect.size() != 4)
            throw InputError(where + ": each \"ignore\" rectangle is [x, y, width, height]");
          int v[4];
          for (size_t k = 0; k < 4; ++k) v[k] = int(number_of(rect[k], where, "ignore", k < 2 ? 0 : 1, 1 << 24));
          rule.mask.rects.push_back({v[0], v[1], v[2], v[3]});
        }
        known = true;
      }
      if (!known) throw InputError(where + ": unknown key \"" + key + "\"");
    }
    if (rule.metric == DiffMetric::kFlip) {
      if (std::count(given.begin(), given.end(), "--failpercent") && !std::count(given.begin(), given.end(), "--fail"))
        throw InputError(where + ": \"failpercent\" needs \"fail\" with the flip metric");
      if (std::count(given.begin(), given.end(), "--warnpercent") && !std::count(given.begin(), given.end(), "--warn"))
        throw InputError(where + ": \"warnpercent\" needs \"warn\" with the flip metric");
      rule.thresholds = flip_thresholds(values, given);
    } else {
      if (rule.pixels_per_degree != 0) throw InputError(where + ": \"ppd\" is FLIP's: give it with \"metric\": \"flip\"");
      rule.thresholds = values;
    }
    rules.push_back(std::move(rule));
  }
  return rules;
}

DiffOptions options_for(const DiffOptions& options, const std::string& name, const DiffRule** matched) {
  if (matched) *matched = nullptr;
  for (const DiffRule& rule : options.rules) {
    if (!glob_match(rule.pattern, name)) continue;
    if (matched) *matched = &rule;
    DiffOptions o = options;
    o.metric = rule.metric;
    o.thresholds = rule.thresholds;
    if (rule.pixels_per_degree != 0) o.pixels_per_degree = rule.pixels_per_degree;
    o.mask.images.insert(o.mask.images.end(), rule.mask.images.begin(), rule.mask.images.end());
    o.mask.rects.insert(o.mask.rects.end(), rule.mask.rects.begin(), rule.mask.rects.end());
    o.rules.clear();
    return o;
  }
  return options;
}

}  // namespace dqskin
