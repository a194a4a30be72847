#include "console.hpp"

#include "exit_codes.hpp"

#include "dqskin/error.hpp"
#include "../lib/base/stderr_lock.hpp"

#include <algorithm>
#include <iostream>

namespace dqskin::cli {

namespace {

// One write of a whole line, under the lock the library takes while it captures stderr.
void print_line(const std::string& line) {
  const std::lock_guard<std::mutex> lock(stderr_mutex());
  std::cerr << line << std::flush;
}

}  // namespace

void print_error(std::string_view message) { print_line("dqskin: " + printable(message) + "\n"); }

void print_error(std::string_view file, std::string_view message) {
  print_line("dqskin: " + printable(file) + ": " + printable(message) + "\n");
}

void print_warning(std::string_view file, std::string_view message) {
  print_line("dqskin: " + printable(file) + ": warning: " + printable(message) + "\n");
}

void print_note(std::string_view file, std::string_view message) {
  print_line("dqskin: " + printable(file) + ": note: " + printable(message) + "\n");
}

void print_input_messages(const std::vector<InputResult>& inputs, bool quiet, bool verbose) {
  for (const InputResult& in : inputs) {
    if (!in.error.empty()) {
      print_error(in.path, in.error);
      continue;
    }
    if (quiet) continue;
    for (const std::string& w : in.warnings) print_warning(in.path, w);
    if (verbose)
      for (const std::string& n : in.notices) print_note(in.path, n);
  }
}

size_t failed_inputs(const std::vector<InputResult>& inputs) {
  return size_t(std::count_if(inputs.begin(), inputs.end(), [](const InputResult& r) { return !r.error.empty(); }));
}

int job_exit_status(const std::vector<InputResult>& inputs, bool quiet, const char* done) {
  const size_t failed = failed_inputs(inputs);
  if (failed == 0) return kSuccess;
  if (failed == inputs.size()) return kUsageOrInputError;
  if (!quiet)
    print_error(std::to_string(failed) + " of " + std::to_string(inputs.size()) + " inputs failed; the others " + done);
  return kSomeInputsFailed;
}

}  // namespace dqskin::cli
