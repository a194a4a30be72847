#include "texel_image.hpp"

#include "../base/image_file.hpp"
#include "../base/oiio_message.hpp"
#include "dqskin/error.hpp"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <thread>

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
  // Fast path: all exponent bits set is infinity or NaN; most bands have none, and the texel is then
  // looked for below.
  bool any = false;
  if (type_ == TexelType::kFloat32) {
    for (size_t i = 0; i + 4 <= data_.size(); i += 4) {
      uint32_t bits;
      std::memcpy(&bits, &data_[i], 4);
      any |= (bits & 0x7f800000u) == 0x7f800000u;
    }
  } else {
    for (size_t i = 0; i + 2 <= data_.size(); i += 2) {
      uint16_t bits;
      std::memcpy(&bits, &data_[i], 2);
      any |= (bits & 0x7c00u) == 0x7c00u;
    }
  }
  if (!any) return {};
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

namespace {
constexpr uint64_t kPrime1 = 0x9e3779b185ebca87ull, kPrime2 = 0xc2b2ae3d27d4eb4full;
uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
uint64_t load64(const uint8_t* p) {
  uint64_t w;
  std::memcpy(&w, p, 8);
  return w;
}
}  // namespace

void TexelDigest::mix(const uint8_t* block) {
  for (int i = 0; i < 4; ++i) lanes_[i] = rotl(lanes_[i] + load64(block + 8 * i) * kPrime2, 31) * kPrime1;
}

void TexelDigest::add(const uint8_t* bytes, size_t size) {
  size_ += size;
  if (tail_size_ > 0) {
    const size_t take = std::min(size, sizeof tail_ - tail_size_);
    std::memcpy(tail_ + tail_size_, bytes, take);
    tail_size_ += take;
    bytes += take;
    size -= take;
    if (tail_size_ < sizeof tail_) return;
    mix(tail_);
    tail_size_ = 0;
  }
  for (; size >= 32; bytes += 32, size -= 32) mix(bytes);
  std::memcpy(tail_, bytes, size);
  tail_size_ = size;
}

uint64_t TexelDigest::value() const {
  uint64_t h = rotl(lanes_[0], 1) + rotl(lanes_[1], 7) + rotl(lanes_[2], 12) + rotl(lanes_[3], 18) + size_;
  for (size_t i = 0; i < tail_size_; ++i) h = rotl(h ^ (tail_[i] * kPrime1), 11) * kPrime2;
  h ^= h >> 33;
  h *= kPrime2;
  h ^= h >> 29;
  return h;
}

struct TexelFileWriter::Impl {
  AtomicFile* file = nullptr;
  std::string temporary;
  TexelType type{};
  size_t width = 0, height = 0, next_row = 0;
  int channels = 0;
  size_t row_bytes = 0;
  std::unique_ptr<OIIO::ImageOutput> exr;  // EXR: rows are compressed and written as chunks fill
  TexelImage png;                          // PNG: the whole image, written at close (libpng is one call)
  std::string compression;                 // EXR
  // EXR: rows [chunk_first, next_row) wait in `chunk` until it holds chunk_rows (a whole number of
  // compression blocks).
  std::vector<uint8_t> chunk;
  size_t chunk_first = 0, chunk_rows = 0;
  bool digesting = false;
  TexelDigest digest;

  [[noreturn]] void fail(const std::string& why) const { throw OutputError(file->path() + ": " + why); }

  // The next rows in order: gathered, and the chunk written once full (all of it at the end).
  void add_exr_rows(const uint8_t* data, size_t rows) {
    while (rows > 0) {
      const size_t held = next_row - chunk_first, take = std::min(rows, chunk_rows - held);
      if (data) std::memcpy(chunk.data() + held * row_bytes, data, take * row_bytes);
      else std::memset(chunk.data() + held * row_bytes, 0, take * row_bytes);
      next_row += take;
      rows -= take;
      if (data) data += take * row_bytes;
      if (next_row - chunk_first == chunk_rows || next_row == height) flush_exr_rows();
    }
  }
  void flush_exr_rows() {
    if (next_row == chunk_first) return;
    if (digesting) digest.add(chunk.data(), (next_row - chunk_first) * row_bytes);
    if (!exr->write_scanlines(int(chunk_first), int(next_row), 0, oiio_type(type), chunk.data()))
      fail(oiio_message(exr->geterror()));
    chunk_first = next_row;
  }
};

bool is_lossless_exr_compression(const std::string& name) {
  return name == "zip" || name == "piz" || name == "rle" || name == "zips" || name == "none";
}

std::string exr_compression(const std::string& requested) { return requested.empty() ? "zip" : requested; }

TexelFileWriter::TexelFileWriter(AtomicFile& file, TexelType type, size_t width, size_t height, int channels,
                                 const std::string& compression, bool digest)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.file = &file;
  m.type = type;
  m.width = width;
  m.height = height;
  m.channels = channels;
  m.digesting = digest;
  m.row_bytes = width * size_t(channels) * channel_bytes(type);
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
  // Scanline (not tiled) with increasing y: the writer holds one chunk of rows, not the image. A chunk is
  // at least 8 MiB and 4 blocks per core, so that every core of OpenEXR's pool has blocks to compress,
  // and at most 64 MiB (one block when a block is larger).
  if (!m.exr->open(m.temporary, spec)) m.fail(oiio_message(m.exr->geterror()));
  const size_t block = rows_per_block(m.compression), block_bytes = block * m.row_bytes;
  const size_t cores = std::max(1u, std::thread::hardware_concurrency());
  size_t blocks = std::max(4 * cores, ((size_t(8) << 20) + block_bytes - 1) / block_bytes);
  blocks = std::max<size_t>(1, std::min(blocks, (size_t(64) << 20) / block_bytes));
  m.chunk_rows = std::min(height, blocks * block);
  m.chunk.resize(m.chunk_rows * m.row_bytes);
}

TexelFileWriter::~TexelFileWriter() = default;

void TexelFileWriter::write(const TexelImage& band) {
  Impl& m = *impl_;
  assert(band.type() == m.type && band.width() == m.width && band.channels() == m.channels);
  assert(band.first_row() >= m.next_row && band.first_row() + band.rows() <= m.height);
  if (m.exr) {
    m.add_exr_rows(nullptr, band.first_row() - m.next_row);  // skipped rows are zeros
    m.add_exr_rows(band.data(), band.rows());
    return;
  }
  std::memcpy(m.png.data() + band.first_row() * m.row_bytes, band.data(), band.rows() * m.row_bytes);
  m.next_row = band.first_row() + band.rows();
}

void TexelFileWriter::close() {
  Impl& m = *impl_;
  if (m.exr) {
    m.add_exr_rows(nullptr, m.height - m.next_row);
    m.flush_exr_rows();
    m.chunk = std::vector<uint8_t>();
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
  if (m.digesting) m.digest.add(m.png.data(), m.height * m.row_bytes);
  io::write_image_file(m.temporary, m.file->path(), "png", spec, oiio_type(m.type), m.png.data());
  m.png = TexelImage();
}

const std::string& TexelFileWriter::temporary() const { return impl_->temporary; }

uint64_t TexelFileWriter::digest() const { return impl_->digest.value(); }

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
