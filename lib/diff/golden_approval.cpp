#include "dqskin/golden_approval.hpp"
#include "../base/output_journal.hpp"

#include "dqskin/atomic_file.hpp"
#include "dqskin/error.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <vector>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

// Copies `from` into the open temporary of `to`, a megabyte at a time.
void copy_into(const std::string& from, AtomicFile& to) {
  std::ifstream in(from, std::ios::binary);
  if (!in) throw InputError(from + ": cannot read the candidate: " + std::strerror(errno));
  std::vector<char> buffer(size_t(1) << 20);
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    const std::streamsize got = in.gcount();
    if (got > 0) to.write(std::span<const char>(buffer.data(), size_t(got)));
  }
  if (in.bad()) throw InputError(from + ": cannot read the candidate: " + std::strerror(errno));
}

}  // namespace

std::vector<Approval> approvals(const DiffReport& report) {
  std::vector<Approval> list;
  std::error_code error;
  const bool golden_folder = fs::is_directory(report.a, error);
  for (const ImageDiff& d : report.pairs) {
    if (d.status != DiffStatus::kFail || d.b.empty() || d.unreadable == d.b) continue;
    if (!fs::is_regular_file(d.b, error)) continue;
    Approval a{d.name, d.a, d.b, false};
    if (a.golden.empty()) {
      if (!golden_folder) continue;
      a.golden = (fs::path(report.a) / d.name).string();
    }
    a.added = !fs::exists(a.golden, error);
    list.push_back(std::move(a));
  }
  return list;
}

void approve(const std::vector<Approval>& list) {
  OutputJournal journal;  // rolls every replaced golden back unless all were written
  for (const Approval& a : list) {
    const fs::path parent = fs::path(a.golden).parent_path();
    if (!parent.empty()) journal.make_folders(parent.string());
    AtomicFile file(a.golden);
    copy_into(a.candidate, file);
    file.commit({Overwrite::kReplace, &journal});
  }
  journal.keep();
}

}  // namespace dqskin
