// What bake and render say about each input on stderr (internal to the CLI).
#pragma once

#include "dqskin/bake.hpp"

#include <iostream>
#include <vector>

namespace dqskin::cli {

// One line per failed input ("dqskin: FILE: problem"), and unless `quiet`, one per loader warning of the
// others ("dqskin: FILE: warning: ..."): parts of the file that were dropped or corrected.
inline void print_input_messages(const std::vector<BakeInputResult>& inputs, bool quiet) {
  for (const BakeInputResult& in : inputs) {
    if (!in.error.empty()) {
      std::cerr << "dqskin: " << in.path << ": " << in.error << '\n';
      continue;
    }
    if (!quiet)
      for (const std::string& w : in.warnings) std::cerr << "dqskin: " << in.path << ": warning: " << w << '\n';
  }
}

}  // namespace dqskin::cli
