// dqskin verify: a folder against every manifest in it.
#include "dqskin/verify.hpp"

#include "folder_check.hpp"

namespace dqskin {

VerifyReport verify_folder(const std::string& folder, unsigned threads, const std::atomic<bool>* cancel) {
  using namespace verify_detail;
  const ManifestSet set = read_manifests(folder, cancel);
  std::vector<const JobManifest*> all;
  for (const JobManifest& m : set.manifests) all.push_back(&m);
  VerifyReport report = check_folder(folder_name(folder), set, all, threads, cancel);
  if (set.manifests.empty() && set.problems.empty())
    report.problems.insert(report.problems.begin(),
                           {"", "manifest", "no manifest.json, render-manifest.json or shard manifest: not a bake or render folder"});
  return report;
}

}  // namespace dqskin
