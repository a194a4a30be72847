#include "output_folder.hpp"

#include <algorithm>

namespace dqskin {

OutputFolder::OutputFolder(const std::string& folder, bool create) {
  if (create) journal_.make_folders(folder);
}

void OutputFolder::keep_if_any_succeeded(const std::vector<InputResult>& inputs) noexcept {
  if (std::any_of(inputs.begin(), inputs.end(), [](const InputResult& in) { return in.error.empty(); })) journal_.keep();
}

}  // namespace dqskin
