// One whole image written through OpenImageIO into an AtomicFile's temporary (internal to the image
// module's writers of rendered frames, contact sheets, PNG textures and diff heat maps; streaming writers
// such as the VAT rows and the GIF keep their own ImageOutput open).
#pragma once

#include "dqskin/atomic_file.hpp"

#include <OpenImageIO/imageio.h>

namespace dqskin::io {

// Writes `pixels` (laid out as `spec` says, in `type`) as a `format` file ("png", "openexr") into `file`'s
// temporary; the caller commits. Any failure is one OutputError naming the file, with what libpng
// printed itself (a full disk: "libpng error: Write Error") folded into the line.
void write_image_file(AtomicFile& file, const char* format, const OIIO::ImageSpec& spec, OIIO::TypeDesc type,
                      const void* pixels);
// The same into a temporary already handed over (`name` is the final name, for messages).
void write_image_file(const std::string& temporary, const std::string& name, const char* format,
                      const OIIO::ImageSpec& spec, OIIO::TypeDesc type, const void* pixels);

}  // namespace dqskin::io
