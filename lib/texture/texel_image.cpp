#include "texel_image.hpp"

#include "../base/image_file.hpp"
#include "../base/oiio_message.hpp"
#include "dqskin/error.hpp"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>

#include <bit>
#include <cassert>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>

namespace dqskin::texture {

namespace {

OIIO::TypeDesc oiio_type(TexelType type) {
  switch (type) {
    case TexelType::kFloat32: return OIIO::TypeDesc::FLOAT;
    case TexelType::kHalf: return OIIO::TypeDesc::HALF;
    case TexelType::kUnorm16: return OIIO::TypeDesc::UINT16;
    case TexelType::kUnorm8: return OIIO::TypeDesc::UINT8;
  }
  return OIIO::TypeDesc::UNKNOWN;
}

// Scanlines per block in an OpenEXR file (the OpenEXR file layout, "Scan Line Blocks"): 1 for NONE, RLE
// and ZIPS, 16 for ZIP, 32 for PIZ.
size_t rows_per_block(const std::string& compression) {
  if (compression == "zip") return 16;
  if (compression == "piz") return 32;
  return 1;
}

// Whether the EXR at `path` is whole, as OpenEXR lays out a single-part scanline image: magic and version,
// the header's attributes up to an empty name, one offset per block of rows, then the blocks, each an
// int32 row and an int32 byte count before its data. Complete when every offset lies in the file and the
// last block (rows increase) ends where the file ends.
bool exr_is_whole(const std::string& path, size_t height, size_t block_rows) {
  static_assert(std::endian::native == std::endian::little, "EXR files are little-endian");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const auto size = uint64_t(std::streamoff(in.tellg()));
  in.seekg(8);
  std::string word;
  auto skip_attribute = [&in, &word]() {
    std::getline(in, word, '\0');  // name; empty after the last attribute
    if (!in || word.empty()) return false;
    std::getline(in, word, '\0');  // type
    int32_t bytes = 0;
    in.read(reinterpret_cast<char*>(&bytes), 4);
    in.seekg(bytes, std::ios::cur);
    return bool(in);
  };
  while (skip_attribute()) {
  }
  std::vector<uint64_t> offsets((height + block_rows - 1) / block_rows);
  in.read(reinterpret_cast<char*>(offsets.data()), std::streamsize(offsets.size() * 8));
  bool whole = bool(in);
  for (uint64_t at : offsets) whole = whole && at > 0 && at + 8 <= size;
  int32_t block[2] = {0, 0};  // first row, bytes
  if (whole) {
    in.seekg(std::streamoff(offsets.back()));
    in.read(reinterpret_cast<char*>(block), 8);
  }
  return whole && in && block[1] >= 0 && offsets.back() + 8 + uint64_t(block[1]) == size;
}

}  // namespace

TexelImage::TexelImage(TexelType type, size_t width, size_t rows, int channels, size_t first_row)
    : type_(type), width_(width), rows_(rows), first_row_(first_row), channels_(channels),
      data_(width * rows * size_t(channels) * channel_bytes(type), 0) {
  assert(channels == 3 || channels == 4);
}

size_t TexelImage::offset(size_t x, size_t y, int c) const {
  assert(x < width_ && y >= first_row_ && y - first_row_ < rows_ && c >= 0 && c < channels_);
  return (((y - first_row_) * width_ + x) * size_t(channels_) + size_t(c)) * channel_bytes(type_);
}

void TexelImage::set(size_t x, size_t y, int c, float value) {
  uint8_t* p = &data_[offset(x, y, c)];
  switch (type_) {
    case TexelType::kFloat32: std::memcpy(p, &value, 4); break;
    case TexelType::kHalf: {
      const uint16_t bits = Imath::half(value).bits();
      std::memcpy(p, &bits, 2);
      break;
    }
    case TexelType::kUnorm16: {
      const auto q = uint16_t(value);
      std::memcpy(p, &q, 2);
      break;
    }
    case TexelType::kUnorm8: *p = uint8_t(value); break;
  }
}

float TexelImage::get(size_t x, size_t y, int c) const {
  const uint8_t* p = &data_[offset(x, y, c)];
  switch (type_) {
    case TexelType::kFloat32: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TexelType::kHalf: {
      uint16_t bits;
      std::memcpy(&bits, p, 2);
      Imath::half h;
      h.setBits(bits);
      return float(h);
    }
    case TexelType::kUnorm16: {
      uint16_t q;
      std::memcpy(&q, p, 2);
      return float(q);
    }
    case TexelType::kUnorm8: return float(*p);
  }
  return 0;
}

void TexelImage::reset(size_t first_row) {
  std::fill(data_.begin(), data_.end(), uint8_t(0));
  first_row_ = first_row;
}

std::string TexelImage::first_non_finite() const {
  if (is_png(type_)) return {};
  for (size_t y = first_row_; y < first_row_ + rows_; ++y)
    for (size_t x = 0; x < width_; ++x)
      for (int c = 0; c < channels_; ++c)
        if (!std::isfinite(get(x, y, c))) {
          std::string at = "(";  // appended, not concatenated: GCC 12's false -Wrestrict
          at += std::to_string(x);
          at += ", ";
          at += std::to_string(y);
          at += ")";
          return at;
        }
  return {};
}

const char* file_extension(TexelType type) { return is_png(type) ? "png" : "exr"; }

struct TexelFileWriter::Impl {
  AtomicFile* file = nullptr;
  std::string temporary;
  TexelType type{};
  size_t width = 0, height = 0, next_row = 0;
  int channels = 0;
  std::unique_ptr<OIIO::ImageOutput> exr;  // EXR: rows are compressed and written as they come
  TexelImage png;                          // PNG: the whole image, written at close (libpng is one call)
  std::string compression;                 // EXR

  [[noreturn]] void fail(const std::string& why) const { throw OutputError(file->path() + ": " + why); }

  void write_exr_rows(const TexelImage& band) {
    if (!exr->write_scanlines(int(band.first_row()), int(band.first_row() + band.rows()), 0, oiio_type(type), band.data()))
      fail(oiio_message(exr->geterror()));
  }
};

bool is_lossless_exr_compression(const std::string& name) {
  return name == "zip" || name == "piz" || name == "rle" || name == "zips" || name == "none";
}

std::string exr_compression(const std::string& requested) { return requested.empty() ? "zip" : requested; }

TexelFileWriter::TexelFileWriter(AtomicFile& file, TexelType type, size_t width, size_t height, int channels,
                                 const std::string& compression)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.file = &file;
  m.type = type;
  m.width = width;
  m.height = height;
  m.channels = channels;
  if (width == 0 || height == 0 || width > size_t(INT_MAX) / 16 || height > size_t(INT_MAX))
    throw InputError(file.path() + ": " + std::to_string(width) + " x " + std::to_string(height) +
                     " texels is not a size an image file holds");
  m.temporary = file.hand_over();
  if (is_png(type)) {
    m.png = TexelImage(type, width, height, channels);
    return;
  }
  m.compression = exr_compression(compression);
  OIIO::ImageSpec spec(int(width), int(height), channels, oiio_type(type));
  // Lossless only, as the texels must reach the shader bit for bit (DWA and B44 are lossy, PXR24 rounds
  // floats to 24 bits). ZIP (zlib over blocks of 16 scanlines, OpenImageIO's level 4) and PIZ (wavelet
  // and Huffman) are decoded by every EXR reader, small ones included (three.js's EXRLoader, tinyexr), and
  // their output depends only on the texels.
  assert(is_lossless_exr_compression(m.compression));
  spec.attribute("compression", m.compression);
  // Byte-identical outputs: OpenImageIO stamps the current time as the EXR attribute capDate unless the
  // spec has a DateTime, so we give an empty one (no capture date).
  spec.attribute("DateTime", "");
  m.exr = OIIO::ImageOutput::create("openexr");
  if (!m.exr) m.fail(oiio_message(OIIO::geterror()));
  // Scanline (not tiled) with increasing y: the writer holds one block of rows, not the image.
  if (!m.exr->open(m.temporary, spec)) m.fail(oiio_message(m.exr->geterror()));
}

TexelFileWriter::~TexelFileWriter() = default;

void TexelFileWriter::write(const TexelImage& band) {
  Impl& m = *impl_;
  assert(band.type() == m.type && band.width() == m.width && band.channels() == m.channels);
  assert(band.first_row() >= m.next_row && band.first_row() + band.rows() <= m.height);
  if (m.exr) {
    if (band.first_row() > m.next_row) {  // skipped rows are zeros
      const TexelImage zeros(m.type, m.width, band.first_row() - m.next_row, m.channels, m.next_row);
      m.write_exr_rows(zeros);
    }
    m.write_exr_rows(band);
  } else {
    const size_t row_bytes = m.width * size_t(m.channels) * channel_bytes(m.type);
    std::memcpy(m.png.data() + band.first_row() * row_bytes, band.data(), band.rows() * row_bytes);
  }
  m.next_row = band.first_row() + band.rows();
}

void TexelFileWriter::close() {
  Impl& m = *impl_;
  if (m.exr) {
    if (m.next_row < m.height) m.write_exr_rows(TexelImage(m.type, m.width, m.height - m.next_row, m.channels, m.next_row));
    if (!m.exr->close()) m.fail(oiio_message(m.exr->geterror()));
    m.exr.reset();
    if (!exr_is_whole(m.temporary, m.height, rows_per_block(m.compression)))
      m.fail("the image is incomplete after writing (is the disk full?)");
    return;
  }
  OIIO::ImageSpec spec(int(m.width), int(m.height), m.channels, oiio_type(m.type));
  // Data, not colour: no sRGB or gAMA chunk, so that no reader converts the values (engines must import
  // these textures as linear data; docs/formats.md, "Encodings").
  spec.attribute("oiio:ColorSpace", "");
  io::write_image_file(m.temporary, m.file->path(), "png", spec, oiio_type(m.type), m.png.data());
  m.png = TexelImage();
}

const std::string& TexelFileWriter::temporary() const { return impl_->temporary; }

struct TexelFileReader::Impl {
  std::string name;
  TexelType type{};
  size_t width = 0, height = 0;
  int channels = 0;
  std::unique_ptr<OIIO::ImageInput> in;
};

TexelFileReader::TexelFileReader(const std::string& path, const std::string& name, TexelType type, size_t width,
                                 size_t height, int channels)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.name = name;
  m.type = type;
  m.width = width;
  m.height = height;
  m.channels = channels;
  m.in = OIIO::ImageInput::open(path);
  if (!m.in) throw OutputError(name + ": cannot be read back: " + oiio_message(OIIO::geterror()));
  const OIIO::ImageSpec& spec = m.in->spec();
  if (size_t(spec.width) != width || size_t(spec.height) != height || spec.nchannels != channels ||
      spec.format != oiio_type(type))
    throw OutputError(name + ": read back as " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                      " texels of " + std::to_string(spec.nchannels) + " " + spec.format.c_str() +
                      " channels, not what was written");
}

TexelFileReader::~TexelFileReader() = default;

void TexelFileReader::read(size_t first, size_t rows, TexelImage& band) {
  Impl& m = *impl_;
  assert(first + rows <= m.height);
  if (band.type() != m.type || band.width() != m.width || band.rows() != rows || band.channels() != m.channels)
    band = TexelImage(m.type, m.width, rows, m.channels, first);
  else
    band.reset(first);
  // EXR hands channels back in the order written (R, G, B, A), though it stores them sorted by name.
  if (!m.in->read_scanlines(0, 0, int(first), int(first + rows), 0, 0, m.channels, oiio_type(m.type), band.data()))
    throw OutputError(m.name + ": cannot be read back: " + oiio_message(m.in->geterror()));
}

}  // namespace dqskin::texture
