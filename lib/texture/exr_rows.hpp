// One EXR image written in pieces of consecutive rows and spliced back (internal to lib): a shard of a bake
// writes the rows it encoded as an EXR of its own whose data window is those rows and whose display window
// is the whole image (TexelFileWriter with TexelRows), and `dqskin merge` joins the pieces into the file one
// process would have written, byte for byte. No pixel is decoded or compressed again: in a single-part
// scanline EXR every block of rows is compressed alone, so a piece that starts on a block boundary holds
// exactly the whole image's blocks for its rows, and only the header's data window and the offset table
// differ (the OpenEXR file layout: magic and version, header attributes up to an empty name, one offset
// per block, then each block as an int32 first row, an int32 byte count and the bytes).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace dqskin::texture {

// Where a piece's parts lie, read from its header and offset table.
struct ExrRowsPiece {
  std::string path;
  std::string header;          // magic, version and attributes through the empty name that ends them
  size_t data_window_at = 0;   // offset in `header` of the dataWindow's 16 bytes (box2i)
  int32_t data[4] = {};        // dataWindow xMin, yMin, xMax, yMax
  int32_t display[4] = {};     // displayWindow
  size_t block_rows = 1;       // scanlines per block, by compression
  std::vector<uint64_t> offsets;  // of the blocks, in the file
  uint64_t file_size = 0;
};

// Reads a piece's header and offset table and checks that its blocks lie one after another in row order
// up to the end of the file. Throws InputError naming the file and what is wrong.
ExrRowsPiece read_exr_rows_piece(const std::string& path);

// Writes the whole image the pieces are rows of, in order, to `sink`. The pieces must have the same
// header but for the data window, and their rows must follow one another from the display window's first
// to its last row, each but the last a whole number of blocks. Throws InputError naming the piece that
// does not fit.
void splice_exr_rows(const std::vector<std::string>& pieces, const std::function<void(std::span<const char>)>& sink);

// The rows of an EXR block for a compression named as OpenImageIO and TexelFileWriter name it ("zip",
// "piz", "rle", "zips", "none").
size_t exr_block_rows(const std::string& compression);

}  // namespace dqskin::texture
