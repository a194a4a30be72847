// How a job's progress is shown, the same for every command that runs one (bake, render): a bar on a
// terminal, redrawn at most ten times a second (frames, frames per second, time left, the animation), or
// with --json-progress one JSON line per report on standard output; nothing with --quiet.
#pragma once

#include "dqskin/job.hpp"

#include <chrono>
#include <mutex>

namespace dqskin::cli {

class ProgressPrinter {
public:
  // `json`: --json-progress; `quiet`: --quiet (the bar is drawn only on a terminal, and never with either).
  ProgressPrinter(bool json, bool quiet);

  // One report; safe to call from the job's worker threads.
  void operator()(const JobProgress& progress);
  // Clears the bar, before the summary or an error is printed.
  void done();

private:
  const bool json_, bar_;
  bool drawn_ = false;
  double last_draw_ = -1;
  std::mutex mutex_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace dqskin::cli
