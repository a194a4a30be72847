// The vocabulary of a job (shared/DESIGN.md "Job"): what every command that walks inputs × clips × frames
// (bake, render, and the commands to come) reports per input, how it reports progress, and how it stops.
#pragma once

#include <cstddef>
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
};

// Where a job is: called as frames finish.
struct JobProgress {
  size_t frames_done = 0, frames_total = 0;
  std::string input, clip;  // what is being worked on now
};

// Which part of a job this process does: the units of work u with u mod count == index (shared/DESIGN.md
// "Job"), so that N processes started with 0/N … N-1/N together do the whole job once.
struct Shard {
  size_t index = 0, count = 1;
  bool owns(size_t unit) const { return unit % count == index; }
  bool whole() const { return count == 1; }
};

// Parses "I/N" (0 ≤ I < N), the --shard flag. Throws InputError.
Shard parse_shard(const std::string& text);

// Thrown out of a job whose cancel flag was set (the command line sets it on SIGINT and SIGTERM).
class JobCancelled : public std::runtime_error {
public:
  JobCancelled() : std::runtime_error("cancelled") {}
};

}  // namespace dqskin
