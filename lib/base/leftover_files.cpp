#include "leftover_files.hpp"

#include <filesystem>
#include <map>
#include <set>

namespace dqskin::leftover_files {
namespace {

bool all_digits(std::string_view s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos;
}

}  // namespace

std::optional<Leftover> parse(std::string_view name) {
  // "." NAME "." KIND "-" PID "-" N, with NAME not empty.
  if (name.size() < 2 || name[0] != '.') return std::nullopt;
  const size_t counter_dash = name.rfind('-');
  if (counter_dash == std::string_view::npos || !all_digits(name.substr(counter_dash + 1))) return std::nullopt;
  const size_t pid_dash = name.rfind('-', counter_dash - 1);
  if (pid_dash == std::string_view::npos || !all_digits(name.substr(pid_dash + 1, counter_dash - pid_dash - 1)))
    return std::nullopt;
  const std::string_view head = name.substr(0, pid_dash);  // "." NAME "." KIND
  for (const std::string_view kind : {std::string_view(".tmp"), std::string_view(".old")}) {
    if (head.size() > kind.size() + 1 && head.substr(head.size() - kind.size()) == kind) {
      return Leftover{std::string(head.substr(1, head.size() - kind.size() - 1)), kind == ".old"};
    }
  }
  return std::nullopt;
}

size_t remove_for(const std::string& root, const std::vector<std::string>& outputs) noexcept {
  namespace fs = std::filesystem;
  size_t removed = 0;
  try {
    std::map<std::string, std::set<std::string>> by_folder;  // folder → the names of outputs in it
    for (const std::string& output : outputs) {
      const size_t slash = output.find_last_of('/');
      by_folder[slash == std::string::npos ? "" : output.substr(0, slash)].insert(
          slash == std::string::npos ? output : output.substr(slash + 1));
    }
    for (const auto& [folder, names] : by_folder) {
      std::error_code ec;
      for (fs::directory_iterator it(fs::path(root) / folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::optional<Leftover> l = parse(it->path().filename().string());
        std::error_code remove_error;
        if (l && names.count(l->target) && fs::remove(it->path(), remove_error)) ++removed;
      }
    }
  } catch (...) {  // a leftover that stays is reported by dqskin verify; the bake itself succeeded
  }
  return removed;
}

}  // namespace dqskin::leftover_files
