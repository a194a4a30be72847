// Texels as a texture file stores them (internal to lib/texture): float32, half, 16- or 8-bit unsigned, 3
// or 4 channels. A TexelImage holds a band of rows of an image (all of them, or one frame's), addressed by
// the image's own row numbers; TexelFileWriter streams bands into an OpenEXR (float, half) or PNG (the
// integer types) file in row order, and TexelFileReader reads bands back for the decode-back check.
// OpenImageIO stays in the .cpp.
#pragma once

#include "texel_encoding.hpp"

#include "dqskin/atomic_file.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dqskin::texture {

class TexelImage {
public:
  TexelImage() = default;
  // Zero texels for rows [first_row, first_row + rows) of an image `width` texels wide.
  TexelImage(TexelType type, size_t width, size_t rows, int channels, size_t first_row = 0);

  TexelType type() const { return type_; }
  size_t width() const { return width_; }
  size_t rows() const { return rows_; }
  size_t first_row() const { return first_row_; }
  int channels() const { return channels_; }

  // Stores channel c of texel (x, y), y a row of the band. `value` must already be representable: an
  // integer in [0, max] for the unorm types, a half value (texel_encoding's to_half) for half.
  void set(size_t x, size_t y, int c, float value);
  // Channel c of texel (x, y) as stored: the integer for unorm types, the value for float and half.
  float get(size_t x, size_t y, int c) const;
  // Sets every texel to zero and moves the band to start at `first_row`.
  void reset(size_t first_row);
  // The first texel whose channel is not finite (float and half), as "(x, y)"; empty when all are.
  std::string first_non_finite() const;

  const uint8_t* data() const { return data_.data(); }
  uint8_t* data() { return data_.data(); }

private:
  size_t offset(size_t x, size_t y, int c) const;

  TexelType type_ = TexelType::kFloat32;
  size_t width_ = 0, rows_ = 0, first_row_ = 0;
  int channels_ = 0;
  std::vector<uint8_t> data_;
};

// The file's extension for a texel type: "exr" for float and half, "png" for the integer types.
const char* file_extension(TexelType type);

// The lossless OpenEXR compressions a texture may use ("zip", "piz", "rle", "zips", "none"); false for
// any other (lossy ones change texels). Empty means ZIP: the smallest files on every texture measured but
// one, where PIZ, 1.2 to 2 times faster to write, was up to 3.2 times larger (docs/PERFORMANCE.md
// "Texture profiles").
bool is_lossless_exr_compression(const std::string& name);
std::string exr_compression(const std::string& requested);

// A 64-bit digest of texel bytes fed in pieces, equal for equal byte sequences however they are cut: what
// the decode-back check remembers of the texels it compared in memory, to prove that the file decodes to
// them (docs/DESIGN.md §4.8). Not cryptographic: it catches a codec, a disk or a hand that changed
// texels, not an adversary. Four lanes of 64-bit multiply-mix over little-endian words keep it at memory
// speed, several GB/s.
class TexelDigest {
public:
  void add(const uint8_t* bytes, size_t size);
  uint64_t value() const;
  uint64_t bytes() const { return size_; }

private:
  void mix(const uint8_t* block);  // 32 bytes
  uint64_t lanes_[4] = {0x9e3779b97f4a7c15ull, 0xc2b2ae3d27d4eb4full, 0x165667b19e3779f9ull, 0x27d4eb2f165667c5ull};
  uint8_t tail_[32] = {};
  size_t tail_size_ = 0;
  uint64_t size_ = 0;
};

// Rows [first, end) of an image; end 0 means every row.
struct TexelRows {
  size_t first = 0, end = 0;
  bool whole() const { return first == 0 && end == 0; }
};

// Writes an image into `file`'s temporary, band after band in row order (the caller commits the file):
// EXR with channels R, G, B(, A), a lossless compression (exr_compression) and no capture date; PNG with
// no colour-space chunk (the values are data, not colours). Rows never written are zeros. Byte-identical
// for equal texels and equal bands, however the rows come in bands and whatever the thread count.
//
// EXR rows are gathered into chunks of many compression blocks (16 rows for ZIP, 32 for PIZ) before they
// go to OpenEXR, whose thread pool compresses the blocks of one write on every core; a frame's few rows
// at a time would keep one core busy. Each block is compressed alone and the blocks are stored in row
// order, so the bytes do not depend on how the rows were gathered.
class TexelFileWriter {
public:
  // Throws OutputError naming the file when it cannot be created, InputError for sizes no file holds.
  // `digest`: keep digest() (the decode-back check wants it; it costs a pass over the bytes). `rows`: an
  // EXR of those rows only (its data window), whose blocks are the whole image's, byte for byte, when its
  // first row starts a block: what a shard writes of a texture for merge to splice (exr_rows.hpp).
  TexelFileWriter(AtomicFile& file, TexelType type, size_t width, size_t height, int channels,
                  const std::string& compression = "", bool digest = false, TexelRows rows = {});
  ~TexelFileWriter();
  TexelFileWriter(const TexelFileWriter&) = delete;
  TexelFileWriter& operator=(const TexelFileWriter&) = delete;

  // The next rows: band.first_row() must be the first row not yet written (rows skipped are zeros), all
  // within the file's rows.
  void write(const TexelImage& band);
  // Writes the remaining rows as zeros, closes the file and checks that it is whole (an EXR's offset
  // table and last block, which a full disk can cut short while OpenImageIO reports nothing).
  void close();
  // The temporary being written (the file's final name comes with the commit).
  const std::string& temporary() const;
  // With `digest`: the digest of every row of the file in row order (zeros included) as handed to it;
  // complete after close().
  uint64_t digest() const;

  // What the image module does behind these calls (texel_files.hpp).
  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

// Reads an image this project wrote, band by band.
class TexelFileReader {
public:
  // `path` may be a temporary; `name` is what messages call the file. Throws OutputError when the file
  // cannot be opened or is not `type` with `channels` channels and the expected size (`rows`: a piece of
  // those rows of the image, as TexelFileWriter writes one).
  TexelFileReader(const std::string& path, const std::string& name, TexelType type, size_t width, size_t height,
                  int channels, TexelRows rows = {});
  ~TexelFileReader();
  TexelFileReader(const TexelFileReader&) = delete;
  TexelFileReader& operator=(const TexelFileReader&) = delete;

  // Rows [first, first + rows) into `band` (reallocated to fit). Throws OutputError.
  void read(size_t first, size_t rows, TexelImage& band);

  // What the image module does behind these calls (texel_files.hpp).
  struct Impl;

private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace dqskin::texture
