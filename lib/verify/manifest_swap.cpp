#include "manifest_swap.hpp"

#include "../base/pending_files.hpp"
#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "../base/output_journal.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>

namespace dqskin::verify_detail {

void swap_in_manifests(const std::string& folder, const std::vector<ManifestText>& written,
                       const std::vector<std::string>& replaced, const std::atomic<bool>* cancel) {
  // Everything that takes time (writing, flushing) before the folder changes: a signal until then leaves it
  // as it was, the temporaries removed by their destructors or by the process that ends at once.
  std::vector<std::unique_ptr<AtomicFile>> files;
  for (const ManifestText& w : written) {
    check_cancelled(cancel);
    files.push_back(std::make_unique<AtomicFile>(folder + "/" + w.name, /*sync=*/false));
    files.back()->write(w.text);
  }
  check_cancelled(cancel);
  sync_folder(folder);
  check_cancelled(cancel);

  // The swap: renames only, microseconds against the quarter of a second a signal gives the work to stop.
  std::vector<std::pair<std::string, std::string>> aside;  // replaced manifest, its hidden name meanwhile
  aside.reserve(replaced.size());
  OutputJournal journal;  // the manifests the new ones replace (an earlier merge's), kept aside meanwhile
  try {
    for (const std::string& name : replaced) {
      std::string path = folder + "/" + name;
      std::string hidden = pending_files::hidden_name(path, "old");
      pending_files::add(hidden, path);  // a process that ends at once moves it back
      if (std::rename(path.c_str(), hidden.c_str()) != 0) {
        const int error = errno;
        pending_files::remove(hidden);
        throw OutputError(path + ": cannot be deleted after the merge: " + std::strerror(error));
      }
      aside.emplace_back(std::move(path), std::move(hidden));
    }
    for (const std::unique_ptr<AtomicFile>& file : files) file->commit({Overwrite::kReplace, &journal});
    check_cancelled(cancel);  // a signal during the swap undoes it: the folder is as it was, or merged
  } catch (...) {
    journal.roll_back();
    for (auto it = aside.rbegin(); it != aside.rend(); ++it) {
      std::rename(it->second.c_str(), it->first.c_str());
      pending_files::remove(it->second);
    }
    throw;
  }
  journal.keep();
  for (const auto& [path, hidden] : aside) {
    ::unlink(hidden.c_str());
    pending_files::remove(hidden);
  }
}

}  // namespace dqskin::verify_detail
