// The files behind TexelFileWriter and TexelFileReader, written and read by the image module
// (texel_files_oiio.cpp in libdqskin_image.so; base/image_module.hpp says why it is apart).
#pragma once

#include "texel_image.hpp"

#include <cstdint>
#include <memory>
#include <string>

namespace dqskin::texture {

struct TexelFileWriter::Impl {
  virtual ~Impl() = default;
  virtual void write(const TexelImage& band) = 0;
  virtual void close() = 0;
  virtual const std::string& temporary() const = 0;
  virtual uint64_t digest() const = 0;
};

struct TexelFileReader::Impl {
  virtual ~Impl() = default;
  virtual void read(size_t first, size_t rows, TexelImage& band) = 0;
};

// The constructors of TexelFileWriter and TexelFileReader, with their contracts.
class TexelFiles {
public:
  virtual std::unique_ptr<TexelFileWriter::Impl> open_writer(AtomicFile& file, TexelType type, size_t width,
                                                             size_t height, int channels,
                                                             const std::string& compression, bool digest,
                                                             TexelRows rows) const = 0;
  virtual std::unique_ptr<TexelFileReader::Impl> open_reader(const std::string& path, const std::string& name,
                                                             TexelType type, size_t width, size_t height,
                                                             int channels, TexelRows rows) const = 0;

protected:
  ~TexelFiles() = default;
};

// The module's TexelFiles, loaded on first call (its entry point: dqskin_texel_files).
const TexelFiles& texel_files();

}  // namespace dqskin::texture
