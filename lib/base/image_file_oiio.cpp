#include "image_file_oiio.hpp"

#include "dqskin/error.hpp"
#include "oiio_message.hpp"
#include "stderr_capture.hpp"

#include <memory>
#include <string>

namespace dqskin::io {

void write_image_file(AtomicFile& file, const char* format, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                      const void* pixels) {
  write_image_file(file.hand_over(), file.path(), format, spec, type, pixels);
}

void write_image_file(const std::string& temporary, const std::string& name, const char* format,
                      const OIIO::ImageSpec& spec, OIIO::TypeDesc type, const void* pixels) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
  if (!out) throw OutputError(name + ": " + oiio_message(OIIO::geterror()));
  CapturedStderr capture;  // libpng prints its own messages; they join our line
  if (!out->open(temporary, spec) || !out->write_image(type, pixels) || !out->close()) {
    const std::string library = capture.finish();
    throw OutputError(with_library_text(name + ": " + oiio_message(out->geterror()), library));
  }
  out.reset();
  capture.finish();
}

}  // namespace dqskin::io
