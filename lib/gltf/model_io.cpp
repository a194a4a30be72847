#include "model_io.hpp"

#include "dqskin/error.hpp"
#include "precheck.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>

namespace dqskin::gltf {
namespace {

struct FsLimits {
  uint64_t max_file_bytes;
  std::string base_dir;
};

// tinygltf looks for external files in the asset's folder and then in the current directory; a glTF
// file's relative URIs mean its own folder only.
bool file_exists(const std::string& path, void* user) {
  const std::string& base = static_cast<FsLimits*>(user)->base_dir;
  if (path.compare(0, base.size() + 1, base + "/") != 0) return false;
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

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

}  // namespace

std::vector<uint8_t> read_regular_file(const std::string& path, uint64_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError(std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw InputError("not a regular file");
  if (uint64_t(st.st_size) > max_bytes)
    throw InputError(std::to_string(st.st_size) + " bytes, more than dqskin reads (" + std::to_string(max_bytes) + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(std::string("cannot open: ") + std::strerror(errno));
  std::vector<uint8_t> bytes(size_t(st.st_size));
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  if (in.gcount() != std::streamsize(bytes.size())) throw InputError("read error");
  return bytes;
}

tinygltf::Model parse_model(std::span<const uint8_t> bytes, const std::string& base_dir, uint64_t max_file_bytes) {
  const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (bytes.size() > UINT32_MAX) throw InputError("larger than 4 GiB, the most glTF allows");
  precheck_json(json_chunk(bytes, glb), max_file_bytes);

  FsLimits limits{max_file_bytes, base_dir};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &limits});
  loader.SetImageLoader(&keep_encoded_image, nullptr);

  tinygltf::Model model;
  std::string err, warn;
  bool ok;
  try {  // tinygltf reports most problems in `err`, but some as standard exceptions
    if (glb) {
      ok = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
    } else {
      ok = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                      unsigned(bytes.size()), base_dir);
    }
  } catch (const std::exception& e) {
    throw InputError(std::string("cannot be parsed (") + e.what() + ")");
  }
  if (!ok) throw InputError(err.empty() ? std::string("not a glTF file") : first_line(err));
  return model;
}

}  // namespace dqskin::gltf
