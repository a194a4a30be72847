#include "dqskin/error.hpp"
#include "dqskin/job.hpp"

namespace dqskin {

Shard parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  auto number = [&](const std::string& s) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos)
      throw InputError("--shard '" + text + "' is not I/N (e.g. 0/4)");
    return size_t(std::stoul(s));
  };
  if (slash == std::string::npos) throw InputError("--shard '" + text + "' is not I/N (e.g. 0/4)");
  Shard shard{number(text.substr(0, slash)), number(text.substr(slash + 1))};
  if (shard.count == 0 || shard.index >= shard.count)
    throw InputError("--shard '" + text + "': I must be at least 0 and less than N");
  return shard;
}

}  // namespace dqskin
