#include "exr_rows.hpp"

#include "dqskin/error.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>

namespace dqskin::texture {
namespace {

static_assert(std::endian::native == std::endian::little, "EXR files are little-endian");

// Scanlines per block by the header's compression code (OpenEXR file layout, "Scan Line Blocks").
size_t block_rows_of(uint8_t code) {
  switch (code) {
    case 0: case 1: case 2: return 1;   // NONE, RLE, ZIPS
    case 3: case 5: return 16;          // ZIP, PXR24
    case 4: case 6: case 7: case 8: return 32;  // PIZ, B44, B44A, DWAA
    case 9: return 256;                 // DWAB
    default: return 0;
  }
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) { throw InputError(path + ": " + why); }

}  // namespace

size_t exr_block_rows(const std::string& compression) {
  if (compression == "zip") return 16;
  if (compression == "piz") return 32;
  return 1;
}

ExrRowsPiece read_exr_rows_piece(const std::string& path) {
  ExrRowsPiece piece;
  piece.path = path;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) refuse(path, "cannot be opened");
  piece.file_size = uint64_t(std::streamoff(in.tellg()));
  in.seekg(0);
  // The header is small (a few hundred bytes); read it byte by byte through the stream's buffer.
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, "\x76\x2f\x31\x01", 4) != 0) refuse(path, "is not an OpenEXR file");
  uint32_t version = 0;
  std::memcpy(&version, magic + 4, 4);
  // Tiled (bit 9), deep (bit 11) and multi-part (bit 12) files have other layouts.
  if ((version & 0xff) != 2 || (version & 0x1a00) != 0) refuse(path, "is not a single-part scanline OpenEXR file");
  piece.header.assign(magic, 8);
  bool have_data = false, have_display = false;
  uint8_t compression = 255;
  auto read_string = [&](std::string& s) {
    s.clear();
    for (char c; in.get(c);) {
      piece.header.push_back(c);
      if (c == '\0') return true;
      if (s.size() == 255) return false;
      s.push_back(c);
    }
    return false;
  };
  for (std::string name, type;;) {
    if (!read_string(name)) refuse(path, "its header is cut short");
    if (name.empty()) break;
    int32_t size = 0;
    if (!read_string(type) || !in.read(reinterpret_cast<char*>(&size), 4) || size < 0 || size > (1 << 24))
      refuse(path, "its header is cut short");
    piece.header.append(reinterpret_cast<const char*>(&size), 4);
    const size_t at = piece.header.size();
    piece.header.resize(at + size_t(size));
    if (!in.read(piece.header.data() + at, size)) refuse(path, "its header is cut short");
    if ((name == "dataWindow" || name == "displayWindow") && (type != "box2i" || size != 16))
      refuse(path, name + " is not a box2i");
    if (name == "dataWindow") {
      std::memcpy(piece.data, piece.header.data() + at, 16);
      piece.data_window_at = at;
      have_data = true;
    } else if (name == "displayWindow") {
      std::memcpy(piece.display, piece.header.data() + at, 16);
      have_display = true;
    } else if (name == "compression" && size == 1) {
      compression = uint8_t(piece.header[at]);
    }
  }
  if (!have_data || !have_display) refuse(path, "its header has no dataWindow or displayWindow");
  piece.block_rows = block_rows_of(compression);
  if (piece.block_rows == 0) refuse(path, "its compression is unknown");
  if (piece.data[2] < piece.data[0] || piece.data[3] < piece.data[1]) refuse(path, "its data window is empty");
  const uint64_t rows = uint64_t(int64_t(piece.data[3]) - piece.data[1] + 1);
  const uint64_t blocks = (rows + piece.block_rows - 1) / piece.block_rows;
  // Every block takes at least its 8-byte offset and 8-byte header: a window larger than the file is a lie.
  if (blocks > (piece.file_size - piece.header.size()) / 16) refuse(path, "its offset table is cut short");
  piece.offsets.resize(blocks);
  if (!in.read(reinterpret_cast<char*>(piece.offsets.data()), std::streamsize(piece.offsets.size() * 8)))
    refuse(path, "its offset table is cut short");
  // Blocks in row order, one after another, the last ending the file: how OpenEXR writes increasing y.
  uint64_t at = piece.header.size() + piece.offsets.size() * 8;
  for (size_t b = 0; b < piece.offsets.size(); ++b) {
    int32_t block[2] = {0, 0};
    if (piece.offsets[b] != at || !in.seekg(std::streamoff(at)) || !in.read(reinterpret_cast<char*>(block), 8) ||
        block[0] != piece.data[1] + int64_t(b * piece.block_rows) || block[1] < 0)
      refuse(path, "its blocks are not stored one after another in row order");
    at += 8 + uint64_t(block[1]);
  }
  if (at != piece.file_size) refuse(path, "its last block does not end the file");
  return piece;
}

void splice_exr_rows(const std::vector<std::string>& paths, const std::function<void(std::span<const char>)>& sink) {
  if (paths.empty()) throw InputError("no EXR pieces to splice");
  std::vector<ExrRowsPiece> pieces;
  for (const std::string& path : paths) pieces.push_back(read_exr_rows_piece(path));
  const ExrRowsPiece& first = pieces.front();
  // Headers compared with the data window left out: the same image, channels, compression and attributes.
  auto without_window = [](const ExrRowsPiece& p) {
    std::string h = p.header;
    std::memset(h.data() + p.data_window_at, 0, 16);
    return h;
  };
  const std::string common = without_window(first);
  int64_t next_row = first.display[1];
  size_t blocks = 0;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const ExrRowsPiece& p = pieces[i];
    if (p.data_window_at != first.data_window_at || without_window(p) != common)
      refuse(p.path, "its header differs from " + first.path + "'s beyond the data window");
    if (p.data[0] != p.display[0] || p.data[2] != p.display[2] || p.data[1] != next_row)
      refuse(p.path, "its rows do not follow the previous piece's (row " + std::to_string(p.data[1]) + ", expected " +
                         std::to_string(next_row) + ")");
    next_row = int64_t(p.data[3]) + 1;
    if (i + 1 < pieces.size() && (next_row - p.data[1]) % int64_t(p.block_rows) != 0)
      refuse(p.path, "it ends inside a block of " + std::to_string(p.block_rows) + " rows");
    blocks += p.offsets.size();
  }
  if (next_row != int64_t(first.display[3]) + 1)
    refuse(pieces.back().path, "the pieces end at row " + std::to_string(next_row - 1) + ", not at the image's last row " +
                                   std::to_string(first.display[3]));

  // The whole image's header: the data window is the display window, as one writer of every row has it.
  std::string header = first.header;
  std::memcpy(header.data() + first.data_window_at, first.display, 16);
  sink(header);
  std::vector<uint64_t> offsets;
  offsets.reserve(blocks);
  uint64_t at = header.size() + blocks * 8;
  for (const ExrRowsPiece& p : pieces) {
    const uint64_t start = p.offsets.front();
    for (uint64_t o : p.offsets) offsets.push_back(at + (o - start));
    at += p.file_size - start;
  }
  sink(std::span(reinterpret_cast<const char*>(offsets.data()), offsets.size() * 8));
  std::vector<char> buffer(size_t(4) << 20);
  for (const ExrRowsPiece& p : pieces) {
    std::ifstream in(p.path, std::ios::binary);
    in.seekg(std::streamoff(p.offsets.front()));
    for (uint64_t left = p.file_size - p.offsets.front(); left > 0;) {
      const size_t n = size_t(std::min<uint64_t>(left, buffer.size()));
      if (!in.read(buffer.data(), std::streamsize(n))) refuse(p.path, "cannot be read");
      sink(std::span<const char>(buffer.data(), n));
      left -= n;
    }
  }
}

}  // namespace dqskin::texture
