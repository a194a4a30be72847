#include "folder_check.hpp"

#include "../base/parallel_for.hpp"
#include "../base/leftover_files.hpp"
#include "../job/job_manifest.hpp"
#include "dqskin/job.hpp"
#include "../base/sha256.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <new>
#include <set>
#include <thread>
#include <tuple>

namespace dqskin::verify_detail {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Listed {
  uint64_t size = 0;
  std::string sha256;
  const std::string* manifest = nullptr;  // the name of the first manifest that lists it
};

std::string leftover_message(const leftover_files::Leftover& l) {
  return l.old ? "an old file kept aside by a run with --force that was killed (of " + l.target + ")"
               : "a temporary file of a write that was killed (of " + l.target + ")";
}

// What a listed file is on disk compared with its record; empty when it matches.
std::optional<FolderProblem> check_file(const fs::path& folder, const std::string& path, const Listed& listed) {
  std::error_code ec;
  const fs::path file = folder / path;
  const fs::file_status status = fs::symlink_status(file, ec);
  if (ec || !fs::exists(status)) return FolderProblem{path, "missing", "missing (listed in " + *listed.manifest + ")"};
  if (!fs::is_regular_file(status))
    return FolderProblem{path, "missing", "is not a regular file (listed in " + *listed.manifest + " as one)"};
  const uintmax_t size = fs::file_size(file, ec);
  if (ec) return FolderProblem{path, "missing", "cannot be read: " + ec.message()};
  if (size != listed.size)
    return FolderProblem{path, "size",
                         std::to_string(size) + " bytes where " + *listed.manifest + " lists " + std::to_string(listed.size) +
                             (size < listed.size ? " (truncated)" : " (grown)")};
  try {
    if (sha256_file(file.string()) != listed.sha256)
      return FolderProblem{path, "hash", "its SHA-256 differs from the one " + *listed.manifest + " lists (the bytes changed)"};
  } catch (const std::bad_alloc&) {
    throw;  // --max-memory's refusal: the whole check's, not this file's
  } catch (const std::exception&) {
    return FolderProblem{path, "missing", "cannot be read"};
  }
  return std::nullopt;
}

// Shards of a job that left no manifest: every count N seen for a job needs all of 0 … N-1. A shard manifest
// that is there but unreadable is a problem of its own (in `present`), not a missing one. Consecutive missing
// shards are one problem, so that what is reported grows with the manifests there, not with the count a
// manifest's name declares (manifest.shard-0-of-999999.json alone is one problem, not 999,998).
void find_missing_shards(const std::vector<const JobManifest*>& manifests, const std::vector<FolderProblem>& present,
                         std::vector<FolderProblem>& problems) {
  std::map<std::pair<std::string, size_t>, std::set<size_t>> seen;  // (base, count) → indices there
  for (const JobManifest* m : manifests)
    if (m->sharded()) seen[{m->base, m->shard.count}].insert(m->shard.index);
  for (const FolderProblem& p : present)
    if (const std::optional<JobManifest> m = parse_manifest_name(p.path); m && m->sharded())
      if (const auto it = seen.find({m->base, m->shard.count}); it != seen.end()) it->second.insert(m->shard.index);
  for (const auto& [job, there] : seen) {
    const std::string& base = job.first;  // not a structured binding: the lambda below captures it
    const size_t count = job.second;
    size_t next = 0;  // the first index not yet accounted for
    auto missing_until = [&](size_t end) {  // indices next … end-1 are missing
      if (next >= end) return;
      const size_t last = end - 1;
      const std::string name = job_manifest::file_name(base, Shard{next, count});
      if (next == last)
        problems.push_back({name, "shard-missing",
                            "missing: shard " + std::to_string(next) + "/" + std::to_string(count) +
                                " did not finish (run it again; a shard all of whose inputs fail writes none)"});
      else
        problems.push_back({name, "shard-missing",
                            "missing, and so are the manifests up to " + job_manifest::file_name(base, Shard{last, count}) +
                                ": shards " + std::to_string(next) + " to " + std::to_string(last) + " of " +
                                std::to_string(count) + " did not finish (run them again; a shard all of whose inputs fail writes none)"});
    };
    for (const size_t index : there) {
      missing_until(index);
      next = index + 1;
    }
    missing_until(count);
  }
}

// Whether folders under `root` (relative, "" for root itself) are reached through a symbolic link: verify
// follows none, so that a link in a copied folder cannot make it read, or walk, what lies elsewhere. Keeps
// the chain of folders of the last one asked about, each with what it is; a folder under one that is a link
// or absent is not looked at. Paths asked in sorted order share their folders with the ones before (what
// lies under one folder sorts together), so each folder is looked at once and the work is linear in the
// paths' length, however deep they nest.
class FolderChain {
public:
  explicit FolderChain(const fs::path& root) : root_(root.string()) {}

  bool linked(std::string_view folder) {
    // Keep the levels that are folders of `folder` too.
    while (!levels_.empty()) {
      const size_t end = levels_.back().end;
      if (folder.size() >= end && folder.compare(0, end, current_, 0, end) == 0 &&
          (folder.size() == end || folder[end] == '/'))
        break;
      levels_.pop_back();
    }
    current_.assign(folder);
    for (size_t start = levels_.empty() ? 0 : levels_.back().end + 1; start < current_.size();) {
      const size_t slash = current_.find('/', start);
      const size_t end = slash == std::string::npos ? current_.size() : slash;
      Level level{end, levels_.empty() ? Kind::kFolder : levels_.back().kind};
      if (level.kind == Kind::kFolder) level.kind = kind_of(root_ + "/" + current_.substr(0, end));
      levels_.push_back(level);
      start = end + 1;
    }
    return !levels_.empty() && levels_.back().kind == Kind::kLinked;
  }

private:
  enum class Kind { kFolder, kLinked, kOther };  // kOther: absent, or not a folder (nothing lies under it)
  struct Level {
    size_t end;  // current_'s first `end` bytes name it
    Kind kind;   // its own, or kLinked / kOther when one above it is
  };
  static Kind kind_of(const std::string& path) {
    std::error_code ec;
    const fs::file_type type = fs::symlink_status(path, ec).type();
    return type == fs::file_type::symlink ? Kind::kLinked : type == fs::file_type::directory ? Kind::kFolder : Kind::kOther;
  }

  const std::string root_;
  std::string current_;
  std::vector<Level> levels_;
};

std::string_view parent_of(std::string_view path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string_view::npos ? std::string_view() : path.substr(0, slash);
}

}  // namespace

VerifyReport check_folder(const fs::path& folder, const ManifestSet& set, const std::vector<const JobManifest*>& manifests,
                          unsigned threads, const std::atomic<bool>* cancel) {
  VerifyReport report;
  report.folder = folder.string();
  report.problems = set.problems;
  for (const std::string& name : set.root_leftovers)
    report.problems.push_back({name, "temporary", leftover_message(*leftover_files::parse(name))});
  find_missing_shards(manifests, set.problems, report.problems);

  // Every listed file once; two manifests that list one path differently are a problem of their own.
  std::map<std::string, Listed> listed;
  std::set<std::string> owned;  // the output folders of inputs that did not fail
  for (const JobManifest* m : manifests) {
    check_cancelled(cancel);
    report.manifests.push_back(m->name);
    for (const json& out : m->json["outputs"]) {
      const Listed entry{out["size"].get<uint64_t>(), out["sha256"].get<std::string>(), &m->name};
      const auto [it, inserted] = listed.emplace(out["path"].get<std::string>(), entry);
      if (!inserted && (it->second.size != entry.size || it->second.sha256 != entry.sha256))
        report.problems.push_back({it->first, "conflict", "listed differently by " + *it->second.manifest + " and " + m->name});
    }
    for (const json& in : m->json["inputs"])
      if (!in.contains("error")) owned.insert(in["output_folder"].get<std::string>());
  }
  report.files = listed.size();
  for (const auto& [path, entry] : listed) report.bytes += entry.size;

  FolderChain folders(folder);
  std::vector<const std::pair<const std::string, Listed>*> files;  // the listed files to look at
  for (const auto& file : listed) {
    if (folders.linked(parent_of(file.first)))
      report.problems.push_back({file.first, "missing", "lies behind a symbolic link, which verify does not follow"});
    else
      files.push_back(&file);
  }
  std::vector<std::optional<FolderProblem>> results(files.size());
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  concurrency::parallel_for(files.size(), threads, [&](size_t i) {
    check_cancelled(cancel);
    results[i] = check_file(folder, files[i]->first, files[i]->second);
  });
  for (std::optional<FolderProblem>& p : results)
    if (p) report.problems.push_back(std::move(*p));

  // The files in the owned folders that no manifest lists. A folder inside another owned one is walked
  // with it, not again (owned folders nested a thousand deep would be walked a thousand times).
  FolderChain stems(folder);
  std::vector<std::string_view> walked;  // the stems walked that may hold the next ones (sorted order)
  for (const std::string& stem : owned) {
    while (!walked.empty() && !(stem.size() > walked.back().size() && stem.compare(0, walked.back().size(), walked.back()) == 0 &&
                                stem[walked.back().size()] == '/'))
      walked.pop_back();
    if (!walked.empty()) continue;
    if (stems.linked(stem)) {
      report.problems.push_back({stem, "unlisted", "is a symbolic link, which verify does not follow"});
      continue;
    }
    walked.push_back(stem);
    std::error_code ec;
    for (fs::recursive_directory_iterator it(folder / stem, ec), end; !ec && it != end; it.increment(ec)) {
      check_cancelled(cancel);
      std::error_code type_error;  // folders hold the files; a link to one is a file here, not followed
      if (it->symlink_status(type_error).type() == fs::file_type::directory) continue;
      const std::string path = stem + "/" + it->path().lexically_relative(folder / stem).generic_string();
      if (const auto leftover = leftover_files::parse(it->path().filename().string()))
        report.problems.push_back({path, "temporary", leftover_message(*leftover)});
      else if (!listed.count(path))
        report.problems.push_back({path, "unlisted", "is not listed in any manifest"});
    }
    if (ec && ec != std::errc::no_such_file_or_directory)
      report.problems.push_back({stem, "missing", "cannot be listed: " + ec.message()});
  }
  // The folder's own problems first (a shard that did not finish explains the files no manifest lists).
  auto rank = [](const FolderProblem& p) { return p.kind == "shard-missing" || p.kind == "manifest" ? 0 : 1; };
  std::sort(report.problems.begin(), report.problems.end(), [&](const FolderProblem& a, const FolderProblem& b) {
    return std::make_tuple(rank(a), std::cref(a.path), std::cref(a.kind)) < std::make_tuple(rank(b), std::cref(b.path), std::cref(b.kind));
  });
  return report;
}

}  // namespace dqskin::verify_detail
