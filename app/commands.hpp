// The dqskin commands: each one a settings struct that CLI11 fills and a function that runs it.
#pragma once

#include <string>
#include <vector>

namespace dqskin::cli {

struct InfoSettings {
  std::vector<std::string> inputs;
  bool json = false;
};

// Prints facts about each input. Returns an ExitCode.
int run_info(const InfoSettings& settings);

}  // namespace dqskin::cli
