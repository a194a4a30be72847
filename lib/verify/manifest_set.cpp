#include "manifest_set.hpp"

#include "../base/leftover_files.hpp"
#include "../job/job_manifest.hpp"
#include "dqskin/error.hpp"
#include "dqskin/job.hpp"
#include "dqskin/memory_ceiling.hpp"
#include "free_unbounded.hpp"

#include <algorithm>
#include <fstream>
#include <new>

namespace dqskin::verify_detail {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A manifest larger than this is not one dqskin wrote (a million outputs take ~150 MB).
constexpr uintmax_t kLargestManifest = uintmax_t(1) << 30;

bool is_count(const json& j) { return j.is_number_unsigned(); }

bool is_sha256(const json& j) {
  if (!j.is_string()) return false;
  const std::string& s = j.get_ref<const std::string&>();
  return s.size() == 64 && s.find_first_not_of("0123456789abcdef") == std::string::npos;
}

// Why `m` is not a manifest verify can rely on, or empty.
std::string shape_problem(const JobManifest& m) {
  const json& j = m.json;
  if (!j.is_object()) return "is not a JSON object";
  const json* shard = j.contains("shard") ? &j["shard"] : nullptr;
  if (!shard || !shard->is_object() || !is_count(shard->value("index", json())) || !is_count(shard->value("count", json())))
    return "has no shard {index, count}";
  if ((*shard)["index"].get<uint64_t>() != m.shard.index || (*shard)["count"].get<uint64_t>() != m.shard.count)
    return "says it is shard " + (*shard)["index"].dump() + " of " + (*shard)["count"].dump() + ", not what its name says";
  if (!j.contains("inputs") || !j["inputs"].is_array()) return "has no inputs list";
  for (size_t i = 0; i < j["inputs"].size(); ++i) {
    const json& in = j["inputs"][i];
    if (!in.is_object() || !in.contains("output_folder") || !in["output_folder"].is_string() ||
        !is_contained_path(in["output_folder"].get_ref<const std::string&>()))
      return "inputs[" + std::to_string(i) + "] has no output_folder inside the folder";
  }
  if (!j.contains("outputs") || !j["outputs"].is_array()) return "has no outputs list";
  for (size_t i = 0; i < j["outputs"].size(); ++i) {
    const json& out = j["outputs"][i];
    const std::string at = "outputs[" + std::to_string(i) + "]";
    if (!out.is_object() || !out.contains("path") || !out["path"].is_string()) return at + " has no path";
    if (!is_contained_path(out["path"].get_ref<const std::string&>())) return at + " names a path outside the folder";
    if (!is_count(out.value("size", json()))) return at + " has no size";
    if (!is_sha256(out.value("sha256", json()))) return at + " has no SHA-256";
  }
  return {};
}

// Builds a document as nlohmann's SAX parser reads the text, and stops the parser where the text nests
// deeper than `deepest` levels, before anything deeper is built. (The parser's own depth callback cannot be
// used: after every object it ends, the DOM parser that calls it searches the whole enclosing list for a
// discarded value, which made a manifest of 400,000 outputs take minutes to read.) The document is the
// caller's, so that when the parser stops, or std::bad_alloc unwinds it, the caller frees what was built
// (free_unbounded).
class BoundedDocument final : public nlohmann::json_sax<json> {
public:
  BoundedDocument(json& root, int deepest) : root_(root), deepest_(deepest) {}
  bool too_deep = false;

  bool null() override { return add(nullptr); }
  bool boolean(bool value) override { return add(value); }
  bool number_integer(number_integer_t value) override { return add(value); }
  bool number_unsigned(number_unsigned_t value) override { return add(value); }
  bool number_float(number_float_t value, const string_t&) override { return add(value); }
  bool string(string_t& value) override { return add(std::move(value)); }
  bool binary(binary_t& value) override { return add(json::binary(std::move(value))); }
  bool key(string_t& name) override {
    key_ = std::move(name);
    return true;
  }
  bool start_object(std::size_t) override { return open(json::object()); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

private:
  // Puts `value` where the text has it: the root, the next element of an array, or the member named by
  // the last key (the last of equal keys wins, as nlohmann's own parser has it). Pointers to the open
  // arrays and objects stay valid: an array grows only while it is the innermost one open.
  json* place(json&& value) {
    if (open_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return &parent.back();
    }
    json& member = parent[key_];
    member = std::move(value);
    return &member;
  }
  bool add(json&& value) {
    place(std::move(value));
    return true;
  }
  bool open(json&& container) {
    if (int(open_.size()) >= deepest_) {
      too_deep = true;
      return false;
    }
    open_.push_back(place(std::move(container)));
    return true;
  }
  bool close() {
    open_.pop_back();
    return true;
  }

  json& root_;
  const int deepest_;
  std::vector<json*> open_;  // the arrays and objects being read, outermost first
  std::string key_;
};

// Reads and parses `path` into `json`; why it is not a manifest, or empty. Nesting is bounded: every
// manifest dqskin writes is 5 levels deep, and the merge walks the document recursively.
std::string parse_manifest_file(const fs::path& path, json& out) {
  constexpr int kDeepest = 32;
  std::error_code size_error;
  const uintmax_t size = fs::file_size(path, size_error);
  std::ifstream file(path, std::ios::binary);
  if (size_error || !file) return "cannot be read";
  if (size > kLargestManifest) return "is larger than any manifest (" + std::to_string(size) + " bytes)";
  std::string text(size_t(size), '\0');  // read at once: a stream's buffer would double, then be copied
  file.read(text.data(), std::streamsize(text.size()));
  if (size_t(file.gcount()) != text.size()) return "cannot be read";
  BoundedDocument document(out, kDeepest);
  if (!json::sax_parse(text, &document)) {
    free_unbounded(out);  // what was built before the parser stopped
    return document.too_deep ? "is nested deeper than " + std::to_string(kDeepest) + " levels" : "is not valid JSON";
  }
  return {};
}

// Reads the manifest at `path` into `m`; why it cannot be relied on, or empty. Throws InputError naming the
// manifest when it takes more memory than --max-memory allows (its document is several times its size).
std::string read_manifest(const fs::path& path, JobManifest& m) {
  try {
    std::string problem = parse_manifest_file(path, m.json);
    if (problem.empty()) problem = shape_problem(m);
    if (!problem.empty()) free_unbounded(m.json);
    return problem;
  } catch (const std::bad_alloc&) {
    free_unbounded(m.json);  // what was read, freed before the message is made
    const MemoryCeilingLifted lifted;
    throw InputError(path.string() + ": " + out_of_memory_message());
  }
}

}  // namespace

std::string folder_name(std::string folder) {
  while (folder.size() > 1 && folder.back() == '/') folder.pop_back();
  return folder;
}

bool is_contained_path(std::string_view path) {
  if (path.empty() || path.front() == '/' || path.find('\0') != std::string_view::npos) return false;
  for (size_t start = 0;;) {
    const size_t slash = path.find('/', start);
    const std::string_view part = path.substr(start, slash == std::string_view::npos ? slash : slash - start);
    if (part.empty() || part == "." || part == "..") return false;
    if (slash == std::string_view::npos) return true;
    start = slash + 1;
  }
}

std::optional<JobManifest> parse_manifest_name(std::string_view name) {
  constexpr std::string_view json_suffix = ".json", shard_infix = ".shard-", of = "-of-";
  if (name.size() <= json_suffix.size() || name.substr(name.size() - json_suffix.size()) != json_suffix) return std::nullopt;
  const std::string_view stem = name.substr(0, name.size() - json_suffix.size());
  for (const std::string_view base : kJobBases) {
    if (stem.substr(0, base.size()) != base) continue;
    const std::string_view rest = stem.substr(base.size());
    if (rest.empty()) return JobManifest{std::string(name), std::string(base), {}, {}};
    if (rest.substr(0, shard_infix.size()) != shard_infix) continue;
    const std::string_view numbers = rest.substr(shard_infix.size());
    const size_t split = numbers.find(of);
    if (split == std::string_view::npos) continue;
    try {
      const Shard shard = parse_shard(std::string(numbers.substr(0, split)) + "/" + std::string(numbers.substr(split + of.size())));
      // Only the spelling a shard writes: "0" and no leading zeros, so that one shard has one name.
      if (job_manifest::file_name(base, shard) != name) continue;
      if (shard.whole()) continue;
      return JobManifest{std::string(name), std::string(base), shard, {}};
    } catch (const InputError&) {
    }
  }
  return std::nullopt;
}

ManifestSet::~ManifestSet() { free_unbounded(manifests); }

ManifestSet read_manifests(const fs::path& folder, const std::atomic<bool>* cancel) {
  ManifestSet set;
  std::error_code ec;
  fs::directory_iterator it(folder, ec);
  if (ec) throw InputError(folder.string() + ": " + (fs::exists(folder) ? "cannot be listed: " + ec.message() : "no such folder"));
  for (fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
    check_cancelled(cancel);
    const std::string name = it->path().filename().string();
    if (leftover_files::parse(name)) {
      set.root_leftovers.push_back(name);
      continue;
    }
    std::optional<JobManifest> m = parse_manifest_name(name);
    if (!m) continue;
    std::string problem;
    std::error_code status_error;
    const fs::file_status status = fs::symlink_status(it->path(), status_error);
    if (fs::is_symlink(status)) problem = "is a symbolic link, which verify does not follow";
    else if (status_error || !fs::is_regular_file(status)) problem = "is not a regular file";  // a FIFO would block
    else problem = read_manifest(it->path(), *m);
    if (problem.empty()) set.manifests.push_back(std::move(*m));
    else set.problems.push_back({name, "manifest", "the manifest " + problem});
  }
  if (ec) throw InputError(folder.string() + ": cannot be listed: " + ec.message());
  std::sort(set.manifests.begin(), set.manifests.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  std::sort(set.root_leftovers.begin(), set.root_leftovers.end());
  return set;
}

}  // namespace dqskin::verify_detail
