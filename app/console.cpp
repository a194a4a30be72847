#include "console.hpp"

#include "dqskin/error.hpp"

#include <iostream>

namespace dqskin::cli {

void print_error(std::string_view message) { std::cerr << "dqskin: " << printable(message) << '\n'; }

void print_error(std::string_view file, std::string_view message) {
  std::cerr << "dqskin: " << printable(file) << ": " << printable(message) << '\n';
}

void print_warning(std::string_view file, std::string_view message) {
  std::cerr << "dqskin: " << printable(file) << ": warning: " << printable(message) << '\n';
}

void print_input_messages(const std::vector<BakeInputResult>& inputs, bool quiet) {
  for (const BakeInputResult& in : inputs) {
    if (!in.error.empty()) {
      print_error(in.path, in.error);
      continue;
    }
    if (!quiet)
      for (const std::string& w : in.warnings) print_warning(in.path, w);
  }
}

}  // namespace dqskin::cli
