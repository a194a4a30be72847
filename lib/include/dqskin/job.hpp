// The vocabulary of a job (docs/DESIGN.md §2.6): what every command that walks inputs × clips × frames
// (bake, render, and the commands to come) reports per input, how it reports progress, and how it stops.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace dqskin {

// One input's outcome.
struct InputResult {
  std::string path;
  std::string error;  // empty when the input succeeded
  size_t frames = 0;  // frames this process deformed (bake) or rendered (render)
  std::vector<std::string> warnings;  // the loader's (Asset::warnings): what it dropped or corrected
  std::vector<std::string> notices;   // the loader's (Asset::notices): printed only with --verbose
};

// Where a job is: called as frames finish.
struct JobProgress {
  size_t frames_done = 0, frames_total = 0;
  std::string input, clip;  // what is being worked on now
};

// Which part of a job this process does: the units of work u with u mod count == index
// (docs/DESIGN.md §6.5), so that N processes started with 0/N … N-1/N together do the whole job once.
struct Shard {
  size_t index = 0, count = 1;
  bool owns(size_t unit) const { return unit % count == index; }
  bool whole() const { return count == 1; }
};

// Parses "I/N" (0 ≤ I < N), the --shard flag. Throws InputError.
Shard parse_shard(const std::string& text);

// Counts a job's finished frames over all its inputs and reports each step; safe to call from several
// threads. Frames of an input that fails later stay counted: progress shows work done, not work kept.
class ProgressCounter {
public:
  ProgressCounter(size_t frames_total, std::function<void(const JobProgress&)> report)
      : total_(frames_total), report_(std::move(report)) {}

  void add(size_t frames, const std::string& input, const std::string& clip) {
    JobProgress p;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done_ += frames;
      p = {done_, total_, input, clip};
    }
    if (report_) report_(p);  // outside the lock: the printer has its own
  }

private:
  const size_t total_;
  const std::function<void(const JobProgress&)> report_;
  std::mutex mutex_;
  size_t done_ = 0;
};

// Thrown out of a job whose cancel flag was set (the command line sets it on SIGINT and SIGTERM).
class JobCancelled : public std::runtime_error {
public:
  JobCancelled() : std::runtime_error("cancelled") {}
};

// The cancellation point of every job: throws JobCancelled once `cancel` (may be null) is set.
inline void check_cancelled(const std::atomic<bool>* cancel) {
  if (cancel && cancel->load()) throw JobCancelled();
}

}  // namespace dqskin
