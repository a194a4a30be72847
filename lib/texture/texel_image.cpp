#include "texel_image.hpp"

#include "texel_files.hpp"
#include "../base/image_module.hpp"
#include "dqskin/error.hpp"

#include <Imath/half.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>

namespace dqskin::texture {


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

bool is_lossless_exr_compression(const std::string& name) {
  return name == "zip" || name == "piz" || name == "rle" || name == "zips" || name == "none";
}

std::string exr_compression(const std::string& requested) { return requested.empty() ? "zip" : requested; }

TexelFileWriter::TexelFileWriter(AtomicFile& file, TexelType type, size_t width, size_t height, int channels,
                                 const std::string& compression, bool digest, TexelRows rows)
    : impl_(texel_files().open_writer(file, type, width, height, channels, compression, digest, rows)) {}

TexelFileWriter::~TexelFileWriter() = default;

void TexelFileWriter::write(const TexelImage& band) { impl_->write(band); }

void TexelFileWriter::close() { impl_->close(); }

const std::string& TexelFileWriter::temporary() const { return impl_->temporary(); }

uint64_t TexelFileWriter::digest() const { return impl_->digest(); }

TexelFileReader::TexelFileReader(const std::string& path, const std::string& name, TexelType type, size_t width,
                                 size_t height, int channels, TexelRows rows)
    : impl_(texel_files().open_reader(path, name, type, width, height, channels, rows)) {}

TexelFileReader::~TexelFileReader() = default;

void TexelFileReader::read(size_t first, size_t rows, TexelImage& band) { impl_->read(first, rows, band); }

const TexelFiles& texel_files() {
  static const TexelFiles& files = image_module_part<TexelFiles>("dqskin_texel_files");
  return files;
}

}  // namespace dqskin::texture
