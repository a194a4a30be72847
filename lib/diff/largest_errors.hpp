// The largest errors of a frame, for its percentile (internal to lib/diff's geometric diff).
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <vector>

namespace dqskin::diff_detail {

// The `keep` largest of the values added, as a min-heap: the smallest of them is the percentile that
// leaves `keep` − 1 values above it. Most values are below the heap's least and cost one comparison, so
// this is cheaper than keeping every value for a selection. NaNs are not kept (they fail the frame anyway).
class LargestErrors {
public:
  void reset(size_t keep) { keep_ = keep, heap_.clear(); }
  void add(float e) {
    if (heap_.size() < keep_) {
      if (!(e == e)) return;
      heap_.push_back(e);
      std::push_heap(heap_.begin(), heap_.end(), std::greater<float>());
    } else if (e > heap_.front()) {
      std::pop_heap(heap_.begin(), heap_.end(), std::greater<float>());
      heap_.back() = e;
      std::push_heap(heap_.begin(), heap_.end(), std::greater<float>());
    }
  }
  float least() const { return heap_.empty() ? 0.0f : heap_.front(); }

private:
  size_t keep_ = 1;
  std::vector<float> heap_;
};

}  // namespace dqskin::diff_detail
