#include "resource_root.hpp"

#include "dqskin/error.hpp"
#include "../base/file_kind.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

namespace dqskin::gltf {
namespace {

namespace fs = std::filesystem;

// The real path of `path` (every symbolic link, "." and ".." resolved), or "" with errno set.
std::string real_path(const std::string& path) {
  const std::unique_ptr<char, decltype(&std::free)> resolved(::realpath(path.c_str(), nullptr), &std::free);
  return resolved ? std::string(resolved.get()) : std::string();
}

// RFC 3986 §3.1: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ), then ':' before any '/'.
bool has_scheme(const std::string& uri) {
  const size_t colon = uri.find(':');
  if (colon == std::string::npos || colon == 0 || uri.find('/') < colon) return false;
  if (!std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  for (size_t i = 1; i < colon; ++i) {
    const char c = uri[i];
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return true;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string percent_decode(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      out += uri[i];
      continue;
    }
    const int high = i + 2 < uri.size() ? hex_digit(uri[i + 1]) : -1;
    const int low = high >= 0 ? hex_digit(uri[i + 2]) : -1;
    if (low < 0) throw InputError("'%' at byte " + std::to_string(i) + " is not followed by two hex digits");
    if (high == 0 && low == 0) throw InputError("decodes to a NUL byte (%00)");
    out += char(high * 16 + low);
    i += 2;
  }
  return out;
}

ResourceRoot::ResourceRoot(const std::string& model_dir, const std::vector<std::string>& extra)
    : model_dir_(model_dir.empty() ? "." : model_dir), model_root_(real_path(model_dir_)) {
  if (!model_root_.empty()) roots_.push_back(model_root_);
  for (const std::string& dir : extra) {
    const std::string real = real_path(dir);  // realpath leaves no trailing '/'
    if (real.empty()) throw InputError("resource root " + dir + ": " + std::strerror(errno));
    roots_.push_back(real);
  }
}

bool ResourceRoot::inside(const std::string& path) const {
  for (const std::string& root : roots_)
    if (root == "/" || (path.size() > root.size() && path.compare(0, root.size(), root) == 0 && path[root.size()] == '/'))
      return true;
  return false;
}

bool ResourceRoot::check(const std::string& uri, const std::string& what) const {
  const std::string named = what + " uri '" + uri + "'";
  if (has_scheme(uri)) throw InputError(named + " has a scheme; dqskin reads only files relative to the model");
  std::string decoded;
  try {
    decoded = percent_decode(uri);
  } catch (const InputError& e) {
    throw InputError(named + ": " + e.what());
  }
  if (decoded.empty()) throw InputError(named + " is empty");
  if (decoded.front() == '/') throw InputError(named + " is an absolute path; dqskin reads only files relative to the model");
  if (model_root_.empty()) throw InputError(named + ": the model's folder " + model_dir_ + " cannot be resolved");
  const std::string joined = folder_prefix() + decoded;
  const std::string real = real_path(joined);
  if (real.empty()) {
    if (errno != ENOENT) throw InputError(named + ": " + std::strerror(errno));
    // Missing: still refuse a path that leaves every root on its face ("../../secret/x.bin").
    const std::string lexical = (fs::path(model_root_) / decoded).lexically_normal().string();
    if (!inside(lexical))
      throw InputError(named + " leads outside the model's folder" + (roots_.size() > 1 ? " and the resource roots" : "") +
                       "; dqskin does not read it");
    return false;
  }
  if (!inside(real))
    throw InputError(named + " leads outside the model's folder" + (roots_.size() > 1 ? " and the resource roots" : "") +
                     " (to " + real + "); dqskin does not read it");
  struct stat st {};
  if (::stat(real.c_str(), &st) != 0) throw InputError(named + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw InputError(named + " is " + file_kind(st.st_mode) + ", not a regular file");
  return true;
}

uint64_t ResourceRoot::size_of(const std::string& uri) const {
  struct stat st {};
  return ::stat((folder_prefix() + percent_decode(uri)).c_str(), &st) == 0 ? uint64_t(st.st_size) : 0;
}

bool ResourceRoot::allows(const std::string& path) const {
  const std::string prefix = folder_prefix();
  if (path.compare(0, prefix.size(), prefix) != 0) return false;  // tinygltf's "./" search: another file than meant
  const std::string real = real_path(path);
  struct stat st {};
  return !real.empty() && inside(real) && ::stat(real.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace dqskin::gltf
