// TexelFileWriter's and TexelFileReader's files through OpenImageIO: EXR written in chunks of rows that
// OpenEXR's pool compresses on every core, PNG written whole; read back band by band. Part of the image
// module (base/image_module.hpp).
#include "texel_files.hpp"

#include "exr_rows.hpp"

#include "../base/image_file_oiio.hpp"
#include "../base/oiio_message.hpp"
#include "dqskin/error.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cassert>
#include <climits>
#include <cstring>
#include <stdexcept>
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

class OiioTexelWriter final : public TexelFileWriter::Impl {
public:
  AtomicFile* file = nullptr;
  std::string temporary_path;
  TexelType type{};
  size_t width = 0, height = 0, next_row = 0;
  size_t first_row = 0, end_row = 0;  // the rows this file holds (EXR: its data window), of `height`
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
  TexelDigest row_digest;

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
      if (next_row - chunk_first == chunk_rows || next_row == end_row) flush_exr_rows();
    }
  }
  void flush_exr_rows() {
    if (next_row == chunk_first) return;
    if (digesting) row_digest.add(chunk.data(), (next_row - chunk_first) * row_bytes);
    if (!exr->write_scanlines(int(chunk_first), int(next_row), 0, oiio_type(type), chunk.data()))
      fail(oiio_message(exr->geterror()));
    chunk_first = next_row;
  }

  OiioTexelWriter(AtomicFile& output, TexelType texel_type, size_t image_width, size_t image_height,
                  int image_channels, const std::string& requested_compression, bool keep_digest, TexelRows rows)
      : file(&output), type(texel_type), width(image_width), height(image_height), channels(image_channels),
        digesting(keep_digest) {
    first_row = next_row = chunk_first = rows.first;
    end_row = rows.whole() ? height : rows.end;
    row_bytes = width * size_t(channels) * channel_bytes(type);
    if (width == 0 || height == 0 || width > size_t(INT_MAX) / 16 || height > size_t(INT_MAX))
      throw InputError(output.path() + ": " + std::to_string(width) + " x " + std::to_string(height) +
                       " texels is not a size an image file holds");
    temporary_path = output.hand_over();
    if (first_row >= end_row || end_row > height)
      throw std::logic_error("TexelFileWriter: rows " + std::to_string(first_row) + " to " + std::to_string(end_row) +
                             " of an image " + std::to_string(height) + " high");
    if (is_png(type)) {
      if (first_row != 0 || end_row != height)
        throw std::logic_error("TexelFileWriter: a PNG is one compressed stream and holds the whole image");
      png = TexelImage(type, width, height, channels);
      return;
    }
    compression = exr_compression(requested_compression);
    OIIO::ImageSpec spec(int(width), int(end_row - first_row), channels, oiio_type(type));
    // Some rows of the image (exr_rows.hpp): the data window is those rows, the display window the image.
    spec.y = int(first_row);
    spec.full_height = int(height);
    // Lossless only, as the texels must reach the shader bit for bit (DWA and B44 are lossy, PXR24 rounds
    // floats to 24 bits). ZIP (zlib over blocks of 16 scanlines, OpenImageIO's level 4) and PIZ (wavelet
    // and Huffman) are decoded by every EXR reader, small ones included (three.js's EXRLoader, tinyexr), and
    // their output depends only on the texels.
    assert(is_lossless_exr_compression(compression));
    spec.attribute("compression", compression);
    // Byte-identical outputs: OpenImageIO stamps the current time as the EXR attribute capDate unless the
    // spec has a DateTime, so we give an empty one (no capture date).
    spec.attribute("DateTime", "");
    exr = OIIO::ImageOutput::create("openexr");
    if (!exr) fail(oiio_message(OIIO::geterror()));
    // Scanline (not tiled) with increasing y: the writer holds one chunk of rows, not the image. A chunk is
    // at least 8 MiB and 4 blocks per core, so that every core of OpenEXR's pool has blocks to compress,
    // and at most 64 MiB (one block when a block is larger).
    if (!exr->open(temporary_path, spec)) fail(oiio_message(exr->geterror()));
    const size_t block = exr_block_rows(compression), block_bytes = block * row_bytes;
    const size_t cores = std::max(1u, std::thread::hardware_concurrency());
    size_t blocks = std::max(4 * cores, ((size_t(8) << 20) + block_bytes - 1) / block_bytes);
    blocks = std::max<size_t>(1, std::min(blocks, (size_t(64) << 20) / block_bytes));
    chunk_rows = std::min(end_row - first_row, blocks * block);
    chunk.resize(chunk_rows * row_bytes);
  }

  void write(const TexelImage& band) override {
    assert(band.type() == type && band.width() == width && band.channels() == channels);
    assert(band.first_row() >= next_row && band.first_row() + band.rows() <= end_row);
    if (exr) {
      add_exr_rows(nullptr, band.first_row() - next_row);  // skipped rows are zeros
      add_exr_rows(band.data(), band.rows());
      return;
    }
    std::memcpy(png.data() + band.first_row() * row_bytes, band.data(), band.rows() * row_bytes);
    next_row = band.first_row() + band.rows();
  }

  void close() override {
    if (exr) {
      add_exr_rows(nullptr, end_row - next_row);
      flush_exr_rows();
      chunk = std::vector<uint8_t>();
      if (!exr->close()) fail(oiio_message(exr->geterror()));
      exr.reset();
      // Whole as OpenEXR lays it out (exr_rows.hpp), which a full disk can cut short while OpenImageIO
      // reports nothing: every block of the rows written, one after another, the last ending the file.
      bool whole = false;
      try {
        const ExrRowsPiece written = read_exr_rows_piece(temporary_path);
        whole = size_t(written.data[1]) == first_row && size_t(written.data[3]) + 1 == end_row;
      } catch (const InputError&) {
      }
      if (!whole) fail("the image is incomplete after writing (is the disk full?)");
      return;
    }
    OIIO::ImageSpec spec(int(width), int(height), channels, oiio_type(type));
    // Data, not colour: no sRGB or gAMA chunk, so that no reader converts the values (engines must import
    // these textures as linear data; docs/formats.md, "Encodings").
    spec.attribute("oiio:ColorSpace", "");
    if (digesting) row_digest.add(png.data(), height * row_bytes);
    io::write_image_file(temporary_path, file->path(), "png", spec, oiio_type(type), png.data());
    png = TexelImage();
  }

  const std::string& temporary() const override { return temporary_path; }
  uint64_t digest() const override { return row_digest.value(); }
};

class OiioTexelReader final : public TexelFileReader::Impl {
public:
  OiioTexelReader(const std::string& path, const std::string& file_name, TexelType texel_type, size_t image_width,
                  size_t image_height, int image_channels, TexelRows rows)
      : name(file_name), type(texel_type), width(image_width), height(image_height), channels(image_channels) {
    in = OIIO::ImageInput::open(path);
    if (!in) throw OutputError(name + ": cannot be read back: " + oiio_message(OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    const size_t first = rows.first, end = rows.whole() ? height : rows.end;
    if (size_t(spec.width) != width || size_t(spec.height) != end - first || size_t(spec.y) != first ||
        size_t(spec.full_height) != height || spec.nchannels != channels || spec.format != oiio_type(type))
      throw OutputError(name + ": read back as " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                        " texels of " + std::to_string(spec.nchannels) + " " + spec.format.c_str() +
                        " channels, not what was written");
  }

  void read(size_t first, size_t rows, TexelImage& band) override {
    assert(first + rows <= height);
    if (band.type() != type || band.width() != width || band.rows() != rows || band.channels() != channels)
      band = TexelImage(type, width, rows, channels, first);
    else
      band.reset(first);
    // EXR hands channels back in the order written (R, G, B, A), though it stores them sorted by name.
    if (!in->read_scanlines(0, 0, int(first), int(first + rows), 0, 0, channels, oiio_type(type), band.data()))
      throw OutputError(name + ": cannot be read back: " + oiio_message(in->geterror()));
  }

private:
  std::string name;
  TexelType type{};
  size_t width = 0, height = 0;
  int channels = 0;
  std::unique_ptr<OIIO::ImageInput> in;
};

class OiioTexelFiles final : public TexelFiles {
public:
  std::unique_ptr<TexelFileWriter::Impl> open_writer(AtomicFile& file, TexelType type, size_t width, size_t height,
                                                     int channels, const std::string& compression,
                                                     bool digest, TexelRows rows) const override {
    return std::make_unique<OiioTexelWriter>(file, type, width, height, channels, compression, digest, rows);
  }
  std::unique_ptr<TexelFileReader::Impl> open_reader(const std::string& path, const std::string& name, TexelType type,
                                                     size_t width, size_t height, int channels,
                                                     TexelRows rows) const override {
    return std::make_unique<OiioTexelReader>(path, name, type, width, height, channels, rows);
  }
};

}  // namespace
}  // namespace dqskin::texture

// The entry point base/image_module.hpp looks up: the address of this folder's TexelFiles.
extern "C" const void* dqskin_texel_files() {
  static const dqskin::texture::OiioTexelFiles files;
  return static_cast<const dqskin::texture::TexelFiles*>(&files);
}
