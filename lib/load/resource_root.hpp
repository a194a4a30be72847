// Where a model's external files may come from (docs/DESIGN.md §5.1: external files
// resolve only inside the input's resource root): the model's own folder and the folders given with
// --resource-root, compared by real path, symbolic links resolved (internal to the loader).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace dqskin::gltf {

class ResourceRoot {
public:
  // `model_dir`: the folder the model's relative URIs start from (a model read from memory may name one
  // that does not exist: then only a file without external URIs loads). `extra`: further folders that
  // files may come from (a shared texture folder); throws InputError when one of them does not exist.
  ResourceRoot(const std::string& model_dir, const std::vector<std::string>& extra);

  // Checks the external URI of a buffer or an image (`what`, for messages) as RFC 3986 and glTF 2.0 §2.8
  // read it: a relative reference, percent-decoded, resolved against the model's folder. Throws InputError
  // naming the URI when it is absolute, has a scheme (file:, http:), resolves outside every root (through
  // "..", or a symbolic link), or names something that is not a regular file (a folder, device, FIFO or
  // socket). Returns false when no such file exists (whether that is an error is the caller's call).
  bool check(const std::string& uri, const std::string& what) const;

  // The size of the file a URI that check() accepted names.
  uint64_t size_of(const std::string& uri) const;

  // Whether `path` (a URI joined to the model's folder, as tinygltf asks for it) is a regular file under a
  // root. tinygltf also looks in the current directory: such a path, which names another file than the
  // URI means, is refused.
  bool allows(const std::string& path) const;

private:
  bool inside(const std::string& real_path) const;
  // The model's folder with a '/' after it, as tinygltf's JoinPath makes it ("/" stays "/").
  std::string folder_prefix() const { return model_dir_.back() == '/' ? model_dir_ : model_dir_ + "/"; }

  std::string model_dir_;
  std::string model_root_;          // the model folder's real path, or empty when it cannot be resolved
  std::vector<std::string> roots_;  // real paths of the model folder and the extra ones, without a trailing '/'
};

// RFC 3986 percent-decoding of a URI's path ("%20" → ' '; '+' stays '+'). Throws InputError for a '%'
// not followed by two hex digits, or a decoded NUL byte.
std::string percent_decode(const std::string& uri);

}  // namespace dqskin::gltf
