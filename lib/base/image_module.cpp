#include "image_module.hpp"

#include <dlfcn.h>

#include <mutex>
#include <stdexcept>
#include <string>

namespace dqskin {
namespace {

struct Module {
  void* handle = nullptr;
  std::string path, problem;
};

// libdqskin_image.so.N lies beside libdqskin.so.N, in the build tree and where both are installed: found
// from this library's own path, so neither LD_LIBRARY_PATH nor the run path of the program matters.
const Module& module() {
  static const Module loaded = [] {
    Module m;
    Dl_info self{};
    if (!dladdr(reinterpret_cast<void*>(&image_module_symbol), &self) || !self.dli_fname) {
      m.path = DQSKIN_IMAGE_MODULE;
      m.problem = "dqskin's own library path is unknown";
      return m;
    }
    const std::string library = self.dli_fname;
    const size_t slash = library.rfind('/');
    m.path = (slash == std::string::npos ? std::string() : library.substr(0, slash + 1)) + DQSKIN_IMAGE_MODULE;
    // RTLD_NOW: a module from another build fails here, at load, rather than at some later call.
    m.handle = dlopen(m.path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!m.handle) {
      const char* why = dlerror();
      m.problem = why ? why : "the loader gave no reason";
      // glibc's message starts with the path, which ours already names.
      if (m.problem.rfind(m.path + ": ", 0) == 0) m.problem.erase(0, m.path.size() + 2);
    }
    return m;
  }();
  return loaded;
}

}  // namespace

void* image_module_symbol(const char* symbol) {
  const Module& m = module();
  if (!m.handle) throw std::runtime_error("cannot load dqskin's image module " + m.path + ": " + m.problem);
  // dlsym's result is read through dlerror; the module is ours, so a missing entry is a build mismatch.
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  dlerror();
  void* address = dlsym(m.handle, symbol);
  if (!address) {
    const char* why = dlerror();
    throw std::runtime_error("dqskin's image module " + m.path + " has no " + symbol + ": " +
                             (why ? why : "the loader gave no reason"));
  }
  return address;
}

}  // namespace dqskin
