// The image module: libdqskin_image.so holds every file the library reads or writes through OpenImageIO
// (the *_oiio.cpp files of draw/, texture/ and diff/) and is loaded on first use. OpenImageIO's dependency
// closure on Debian (OpenCV, FFmpeg, GDAL, HDF5, OpenVDB: about 260 shared libraries) costs a process
// about 0.25 s to map before main(); commands that touch no image (info, lint, most bakes) never pay it.
// docs/ARCHITECTURE.md, "The image module".
#pragma once

namespace dqskin {

// The address of `symbol` (an extern "C" entry point of one folder's OpenImageIO side) in the image module,
// loaded beside libdqskin on first call. Throws std::runtime_error naming the module and the loader's
// reason when it cannot be loaded (a broken installation).
void* image_module_symbol(const char* symbol);

// One folder's interface to its OpenImageIO side: the object its entry point `symbol` returns. An entry
// point is extern "C" and returns `const void*`, the address of a static `Interface` of the module.
template <class Interface>
const Interface& image_module_part(const char* symbol) {
  using Entry = const void* (*)();
  return *static_cast<const Interface*>(reinterpret_cast<Entry>(image_module_symbol(symbol))());
}

}  // namespace dqskin
