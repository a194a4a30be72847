#include "dqskin/verify.hpp"

#include "free_unbounded.hpp"

#include <nlohmann/json.hpp>

namespace dqskin {

std::string problem_location(const std::string& folder, const FolderProblem& problem) {
  std::string location = folder;
  while (location.size() > 1 && location.back() == '/') location.pop_back();
  if (!problem.path.empty()) location += (location == "/" ? "" : "/") + problem.path;
  return location;
}

std::string verify_json(const VerifyReport& report) {
  using nlohmann::json;
  // Freed whatever --max-memory says (free_unbounded.hpp): a folder can have a problem per listed file.
  json problems = json::array(), doc;
  const verify_detail::FreedUnbounded<json> free_problems(problems), free_doc(doc);
  for (const FolderProblem& p : report.problems)
    problems.push_back({{"path", p.path}, {"kind", p.kind}, {"message", p.message}});
  doc = {{"folder", report.folder},   {"ok", report.ok()},       {"manifests", report.manifests},
         {"files", report.files},     {"bytes", report.bytes},   {"problems", std::move(problems)}};
  return doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace dqskin
