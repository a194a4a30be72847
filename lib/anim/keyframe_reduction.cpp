#include "keyframe_reduction.hpp"

#include "../base/parallel_for.hpp"

#include <algorithm>
#include <utility>

namespace dqskin {

std::vector<size_t> reduce_keyframes(size_t frames, double budget, const InterpolationError& error, unsigned threads) {
  if (frames <= 2) {
    std::vector<size_t> all;
    for (size_t f = 0; f < frames; ++f) all.push_back(f);
    return all;
  }
  std::vector<size_t> keys = {0, frames - 1};
  std::vector<std::pair<size_t, size_t>> segments = {{0, frames - 1}};
  std::vector<double> errors;
  while (!segments.empty()) {
    // Plain names, not a structured binding: the lambda below captures them (clang 14 cannot).
    const size_t a = segments.back().first, b = segments.back().second;
    segments.pop_back();
    if (b - a < 2) continue;
    errors.assign(b - a - 1, 0.0);
    concurrency::parallel_for(errors.size(), threads, [&](size_t k) { errors[k] = error(a + 1 + k, a, b); });
    const size_t worst = size_t(std::max_element(errors.begin(), errors.end()) - errors.begin());  // the first of equals
    if (!(errors[worst] > budget)) continue;
    const size_t key = a + 1 + worst;
    keys.push_back(key);
    segments.emplace_back(key, b);
    segments.emplace_back(a, key);
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

}  // namespace dqskin
