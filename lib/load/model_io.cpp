#include "model_io.hpp"

#include "dqskin/error.hpp"
#include "../base/file_kind.hpp"
#include "animation_pointer.hpp"
#include "file_signature.hpp"
#include "meshopt.hpp"
#include "precheck.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace dqskin::gltf {
namespace {

struct FsLimits {
  uint64_t max_file_bytes;
  const ResourceRoot& root;
};

// tinygltf looks for external files in the asset's folder and then in the current directory; only files
// inside the resource root exist for it. precheck_json has already refused URIs that lead elsewhere, with
// a message naming them; this holds whatever tinygltf asks for to the same rule.
bool file_exists(const std::string& path, void* user) { return static_cast<FsLimits*>(user)->root.allows(path); }

// tinygltf's default expands the path with wordexp(); a file name is not a shell word.
std::string expand_file_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  try {
    *out = read_regular_file(path, static_cast<FsLimits*>(user)->max_file_bytes);
    return true;
  } catch (const InputError& e) {
    if (err) *err += e.what();
    return false;
  }
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "dqskin does not write through the glTF loader";
  return false;
}

// Keeps each image's encoded bytes for the renderer instead of decoding them now.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->as_is = true;
  image->image.assign(bytes, bytes + size);
  return true;
}

// tinygltf joins its messages with newlines; dqskin's errors are one line.
std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

// The .glb with its JSON chunk replaced by `json` (the other chunks as they were).
std::vector<uint8_t> with_json_chunk(std::span<const uint8_t> glb, std::span<const uint8_t> old_json,
                                     const std::string& json) {
  auto put32 = [](std::vector<uint8_t>& out, size_t value) {
    for (int shift = 0; shift < 32; shift += 8) out.push_back(uint8_t(value >> shift));
  };
  const size_t padded = (json.size() + 3) & ~size_t(3);
  const size_t rest = (size_t(old_json.data() - glb.data()) + old_json.size() + 3) & ~size_t(3);  // next chunk
  const size_t tail = rest < glb.size() ? glb.size() - rest : 0;
  std::vector<uint8_t> out(glb.begin(), glb.begin() + 8);  // magic, version
  put32(out, 12 + 8 + padded + tail);
  put32(out, padded);
  out.insert(out.end(), glb.begin() + 16, glb.begin() + 20);  // "JSON"
  out.insert(out.end(), json.begin(), json.end());
  out.resize(out.size() + padded - json.size(), ' ');
  out.insert(out.end(), glb.end() - std::ptrdiff_t(tail), glb.end());
  return out;
}

}  // namespace

std::string folder_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::vector<uint8_t> read_regular_file(const std::string& path, uint64_t max_bytes) {
  // O_NONBLOCK: opening a FIFO does not wait for a writer. The check is on what was opened, so a file
  // swapped after a check by name cannot slip through.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw InputError(std::string("is ") + file_kind(st.st_mode) + ", not a regular file");
  if (uint64_t(st.st_size) > max_bytes)
    throw InputError(std::to_string(st.st_size) + " bytes, more than dqskin reads (" + std::to_string(max_bytes) + ")");
  std::vector<uint8_t> bytes(size_t(st.st_size));
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(std::string("read error: ") + std::strerror(errno));
    if (n == 0) throw InputError("the file became shorter while it was read");
    done += size_t(n);
  }
  return bytes;
}

ParsedModel parse_model(std::span<const uint8_t> bytes, const std::string& folder, const LoadOptions& options) {
  const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (bytes.size() > UINT32_MAX) throw InputError("larger than 4 GiB, the most glTF allows");
  if (const std::optional<std::string> reason = not_gltf_reason(bytes)) throw InputError(*reason);
  // tinygltf joins URIs to this folder as given: "" would make them relative to the current directory.
  const std::string base_dir = folder.empty() ? "." : folder;
  const ResourceRoot root(base_dir, options.resource_roots);
  const std::span<const uint8_t> json = json_chunk(bytes, glb);
  CheckedJson checked = precheck_json(json, options, root, glb);

  // When the checks removed bad appearance values, tinygltf reads the document without them.
  std::vector<uint8_t> rewritten;
  if (checked.changed) {
    const std::string text = checked.doc.dump();
    rewritten = glb ? with_json_chunk(bytes, json, text) : std::vector<uint8_t>(text.begin(), text.end());
    bytes = rewritten;
    if (bytes.size() > UINT32_MAX) throw InputError("larger than 4 GiB once its bad values are removed");
  }

  FsLimits limits{options.max_file_bytes, root};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &limits});
  loader.SetImageLoader(&keep_encoded_image, nullptr);

  ParsedModel out;
  std::string err, warn;
  bool ok;
  try {  // tinygltf reports most problems in `err`, but some as standard exceptions
    if (glb) {
      ok = loader.LoadBinaryFromMemory(&out.model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
    } else {
      ok = loader.LoadASCIIFromString(&out.model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                      unsigned(bytes.size()), base_dir);
    }
  } catch (const std::exception& e) {
    throw InputError(std::string("cannot be parsed (") + e.what() + ")");
  }
  if (!ok) throw InputError(err.empty() ? std::string("not a glTF file") : first_line(err));
  restore_channels(out.model, checked.doc);  // KHR_animation_pointer's channels have no target.node
  // Compressed views (precheck counted what they decode to against max_memory).
  decode_meshopt(out.model, checked.doc, checked.dataless);
  for (size_t a : checked.unviewed_indices) out.model.accessors[a].bufferView = -1;  // decode_draco fills them
  for (size_t a : checked.unviewed_indices) checked.doc["accessors"][a].erase("bufferView");
  out.doc = std::move(checked.doc);
  out.warnings = std::move(checked.warnings);
  out.json_bytes = checked.json_bytes;
  return out;
}

}  // namespace dqskin::gltf
