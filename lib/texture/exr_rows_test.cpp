// EXR pieces of rows spliced back: the whole image's bytes, byte for byte, for every lossless compression
// and texel type a texture uses; pieces that do not fit together refused with the piece named.
#include "exr_rows.hpp"
#include "texel_image.hpp"

#include "dqskin/error.hpp"
#include "../test_support/read_file.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace dqskin::texture {
namespace {

namespace fs = std::filesystem;
using testing_support::read_file;

struct Case {
  TexelType type;
  int channels;
  const char* compression;
  size_t width, height;
  std::vector<size_t> cuts;  // first rows of the pieces after the first
};

// Texels that compress to something (a smooth ramp with noise, as deformed positions are).
float texel(size_t x, size_t y, int c) {
  uint32_t h = uint32_t(x * 73856093u) ^ uint32_t(y * 19349663u) ^ uint32_t(c) * 83492791u;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  return float(x) * 0.01f + float(y) * 0.1f + float(c) + float(h % 1000) * 1e-4f;
}

TexelImage rows(const Case& k, size_t first, size_t end) {
  TexelImage band(k.type, k.width, end - first, k.channels, first);
  for (size_t y = first; y < end; ++y)  // the image's own row numbers
    for (size_t x = 0; x < k.width; ++x)
      for (int c = 0; c < k.channels; ++c) {
        float value = texel(x, y, c);
        if (k.type == TexelType::kHalf) to_half(value, value);
        band.set(x, y, c, value);
      }
  return band;
}

// Writes rows [first, end) of the case's image (all of them when whole) and commits the file.
void write(const Case& k, const fs::path& path, size_t first, size_t end, bool whole) {
  AtomicFile file(path.string(), false);
  TexelFileWriter writer(file, k.type, k.width, k.height, k.channels, k.compression, false,
                         whole ? TexelRows{} : TexelRows{first, end});
  // Two bands, as frames arrive, so that the writer's gathering of rows into chunks is exercised.
  const size_t middle = first + (end - first) / 2;
  if (middle > first) writer.write(rows(k, first, middle));
  writer.write(rows(k, middle, end));
  writer.close();
  file.commit();
}

std::vector<std::string> write_pieces(const Case& k, const fs::path& folder) {
  std::vector<size_t> bounds{0};
  bounds.insert(bounds.end(), k.cuts.begin(), k.cuts.end());
  bounds.push_back(k.height);
  std::vector<std::string> pieces;
  for (size_t i = 0; i + 1 < bounds.size(); ++i) {
    pieces.push_back((folder / ("piece" + std::to_string(i) + ".exr")).string());
    write(k, pieces.back(), bounds[i], bounds[i + 1], false);
  }
  return pieces;
}

std::string splice(const std::vector<std::string>& pieces) {
  std::string out;
  splice_exr_rows(pieces, [&](std::span<const char> bytes) { out.append(bytes.data(), bytes.size()); });
  return out;
}

TEST(ExrRows, PiecesSpliceToTheWholeImageByteForByte) {
  const testing_support::ScratchDir dir("exr_rows");
  const std::vector<Case> cases = {
      {TexelType::kFloat32, 4, "zip", 37, 100, {32, 48}},       // blocks of 16, the last piece ragged
      {TexelType::kHalf, 3, "zip", 64, 16 * 9 + 5, {16 * 3, 16 * 8}},
      {TexelType::kFloat32, 3, "piz", 20, 70, {32, 64}},       // blocks of 32
      {TexelType::kHalf, 4, "rle", 11, 23, {1, 7, 22}},        // blocks of 1: any row
      {TexelType::kFloat32, 4, "zips", 9, 30, {13}},
      {TexelType::kHalf, 4, "none", 5, 12, {4, 5, 11}},
      {TexelType::kFloat32, 4, "zip", 3, 16, {}},              // one piece: the image itself
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& k = cases[i];
    SCOPED_TRACE("case " + std::to_string(i) + ": " + k.compression);
    const fs::path folder = dir.path() / std::to_string(i);
    fs::create_directories(folder);
    write(k, folder / "whole.exr", 0, k.height, true);
    const std::vector<std::string> pieces = write_pieces(k, folder);
    const std::string whole = read_file(folder / "whole.exr");
    const std::string spliced = splice(pieces);
    ASSERT_EQ(spliced.size(), whole.size());
    EXPECT_TRUE(spliced == whole);
    // Each piece is an EXR of its own rows, not the image: what a shard leaves is no output yet.
    if (pieces.size() > 1) {
      EXPECT_NE(read_file(pieces[0]), whole);
    }
  }
}

TEST(ExrRows, PiecesThatDoNotFitAreRefusedNamingThePiece) {
  const testing_support::ScratchDir dir("exr_rows");
  const Case k{TexelType::kFloat32, 4, "zip", 8, 64, {16, 32, 48}};
  const std::vector<std::string> p = write_pieces(k, dir.path());
  auto refusal = [&](const std::vector<std::string>& pieces) {
    try {
      splice(pieces);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(refusal({p[0], p[1], p[3]}).find(p[3] + ": its rows do not follow"), std::string::npos);  // a gap
  EXPECT_NE(refusal({p[1], p[0], p[2], p[3]}).find(p[1] + ": its rows do not follow"), std::string::npos);
  EXPECT_NE(refusal({p[0], p[1], p[2]}).find("not at the image's last row"), std::string::npos);  // one missing
  EXPECT_NE(refusal({}).find("no EXR pieces"), std::string::npos);

  // A piece ending inside a block, and one of another compression.
  const Case ragged{TexelType::kFloat32, 4, "zip", 8, 64, {20}};
  const fs::path r = dir.path() / "ragged";
  fs::create_directories(r);
  const std::vector<std::string> q = write_pieces(ragged, r);
  EXPECT_NE(refusal(q).find(q[0] + ": it ends inside a block of 16 rows"), std::string::npos);
  const Case piz{TexelType::kFloat32, 4, "piz", 8, 64, {32}};
  const fs::path z = dir.path() / "piz";
  fs::create_directories(z);
  const std::vector<std::string> s = write_pieces(piz, z);
  EXPECT_NE(refusal({p[0], p[1], s[1]}).find(s[1] + ": its header differs"), std::string::npos);

  // A data window that claims rows the file cannot hold (2^31 of them): refused before any table is read.
  {
    const std::string original = read_file(p[1]);
    std::string forged = original;
    const size_t at = forged.find(std::string("dataWindow\0box2i\0", 17));
    ASSERT_NE(at, std::string::npos);
    const int32_t huge = 0x7fffffff;
    std::memcpy(forged.data() + at + 17 + 4 + 12, &huge, 4);  // yMax, after the size and xMin, yMin, xMax
    std::ofstream(p[1], std::ios::binary | std::ios::trunc).write(forged.data(), std::streamsize(forged.size()));
    EXPECT_NE(refusal(p).find(p[1] + ": its offset table is cut short"), std::string::npos) << refusal(p);
    std::ofstream(p[1], std::ios::binary | std::ios::trunc).write(original.data(), std::streamsize(original.size()));
  }

  // A piece cut short, and a file that is no EXR.
  const std::string bytes = read_file(p[2]);
  { std::ofstream(p[2], std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size() - 3)); }
  EXPECT_NE(refusal(p).find(p[2] + ": its"), std::string::npos);
  { std::ofstream(p[2], std::ios::binary | std::ios::trunc) << "not an image"; }
  EXPECT_NE(refusal(p).find(p[2] + ": is not an OpenEXR file"), std::string::npos);
}

}  // namespace
}  // namespace dqskin::texture
