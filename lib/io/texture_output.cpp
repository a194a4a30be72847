// Vertex-animation textures and bone textures as OpenEXR files with JSON side files (shared/DESIGN.md
// "Vertex-animation texture (VAT) layout" and "BoneTexture layout").
#include "dqskin/texture_output.hpp"
#include "oiio_message.hpp"

#include "dqskin/error.hpp"

#include <future>
#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace dqskin {
namespace {

using Json = nlohmann::ordered_json;  // keys in the order written, for people reading the side files

// An RGBA32F EXR being written to `file`'s temporary; the final name is for messages. Members are
// destroyed in reverse order: the image is closed before the AtomicFile removes an uncommitted temporary.
class ExrImage {
public:
  ExrImage(std::string path, size_t width, size_t height) : file_(std::move(path)), temporary_(file_.hand_over()) {
    if (width > size_t(INT_MAX) / 16 || height > size_t(INT_MAX))
      throw InputError(file_.path() + ": " + std::to_string(width) + " x " + std::to_string(height) +
                       " texels is too large for an EXR image");
    height_ = height;
    OIIO::ImageSpec spec(int(width), int(height), 4, OIIO::TypeDesc::FLOAT);  // channels R, G, B, A
    // ZIP: lossless, as the texels must reach the shader bit for bit (DWA and B44 are lossy, PXR24 rounds
    // floats to 24 bits). zlib over blocks of 16 scanlines is decoded by every EXR reader, small ones
    // included, and its output depends only on the bytes and the level (OpenImageIO's default, 4). On the
    // Fox it stores 62-71 % of the raw size; PIZ came within 15 % either way, RLE and ZIPS larger.
    spec.attribute("compression", "zip");
    // Byte-identical outputs (DESIGN.md "Determinism"): OpenImageIO stamps the current time as the EXR
    // attribute capDate unless the spec has a DateTime, so we give an empty one (no capture date). A null
    // string would leave capDate out, but OpenImageIO then prints a debug line for every file. It adds no
    // software name or other varying attribute (the tests check the header and the bytes).
    spec.attribute("DateTime", "");
    out_ = OIIO::ImageOutput::create("openexr");
    if (!out_) throw OutputError(file_.path() + ": " + oiio_message(OIIO::geterror()));
    // Scanline (not tiled) with increasing Y: rows are compressed and written as they come, so the writer
    // holds one block of rows, not the image.
    if (!out_->open(temporary_, spec)) fail();
  }

  // Rows [y, y + rows) as RGBA floats, in order after the rows before them.
  void write_rows(size_t y, size_t rows, const float* rgba) {
    assert(out_);
    if (!out_->write_scanlines(int(y), int(y + rows), 0, OIIO::TypeDesc::FLOAT, rgba)) fail();
  }

  void write_all(const float* rgba) {
    if (!out_->write_image(OIIO::TypeDesc::FLOAT, rgba)) fail();
  }

  // Writes the rest of the file (line offsets) and closes it, then checks that it is whole: OpenEXR writes
  // its offset table and the stream's last bytes while closing, where OpenImageIO reports no failure.
  void close() {
    if (!out_) return;
    if (!out_->close()) fail();
    out_.reset();
    check_complete();
  }

  AtomicFile& file() { return file_; }
  const std::string& temporary() const { return temporary_; }

private:
  [[noreturn]] void fail() { throw OutputError(file_.path() + ": " + oiio_message(out_->geterror())); }

  // The file as OpenEXR lays out a single-part scanline image: magic and version, the header's attributes
  // up to an empty name, one offset per block of 16 rows (ZIP), then the blocks, each an int32 row and an
  // int32 byte count before its data. Complete when every offset lies in the file and the last block (rows
  // increase) ends where the file ends.
  void check_complete() {
    static_assert(std::endian::native == std::endian::little, "EXR files are little-endian");
    std::ifstream in(temporary_, std::ios::binary | std::ios::ate);
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
    std::vector<uint64_t> offsets((height_ + 15) / 16);
    in.read(reinterpret_cast<char*>(offsets.data()), std::streamsize(offsets.size() * 8));
    bool whole = bool(in);
    for (uint64_t at : offsets) whole = whole && at > 0 && at + 8 <= size;
    int32_t block[2] = {0, 0};  // first row, bytes
    if (whole) {
      in.seekg(std::streamoff(offsets.back()));
      in.read(reinterpret_cast<char*>(block), 8);
    }
    if (!whole || !in || block[1] < 0 || offsets.back() + 8 + uint64_t(block[1]) != size)
      throw OutputError(file_.path() + ": the image is incomplete after writing (is the disk full?)");
  }

  AtomicFile file_;
  std::string temporary_;
  size_t height_ = 0;
  std::unique_ptr<OIIO::ImageOutput> out_;
};

// A side file: written by name to its AtomicFile's temporary (handed over at once, like the images, so
// that all outputs are committed the same way).
class TextFile {
public:
  explicit TextFile(std::string path) : file_(std::move(path)), temporary_(file_.hand_over()) {}

  void write(const std::string& text) {
    std::ofstream out(temporary_, std::ios::binary | std::ios::trunc);
    out.write(text.data(), std::streamsize(text.size()));
    out.close();
    if (!out) throw OutputError(file_.path() + ": cannot write");
  }

  AtomicFile& file() { return file_; }
  const std::string& temporary() const { return temporary_; }

private:
  AtomicFile file_;
  std::string temporary_;
};


// Commits the files in order. Under kRefuseDifferent they are all compared first, so that a refusal leaves
// every final name as it was (AtomicFile alone would refuse file by file, after renaming the earlier ones).
std::vector<Committed> commit_all(const std::vector<AtomicFile*>& files, const CommitOptions& options) {
  if (options.overwrite == Overwrite::kRefuseDifferent)
    for (const AtomicFile* f : files)
      if (f->conflicts()) throw OutputError(f->path() + ": exists with different contents; not overwritten");
  std::vector<Committed> result;
  for (AtomicFile* f : files) result.push_back(f->commit(options));
  return result;
}

// How the side file names a file: relative to the side file's folder, so the outputs can move together.
std::string name_from(const std::string& json_path, const std::string& path) {
  namespace fs = std::filesystem;
  return fs::path(path).lexically_proximate(fs::path(json_path).parent_path()).generic_string();
}

Json fps_json(double fps) { return fps > 0 ? Json(fps) : Json(nullptr); }

// Node and mesh names come from the file: invalid UTF-8 is replaced rather than refused.
std::string dump(const Json& json) { return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n"; }

size_t total_vertices(const std::vector<VatSource>& sources) {
  size_t n = 0;
  for (const VatSource& s : sources) n += s.vertices;
  return n;
}

}  // namespace

std::vector<VatSource> vat_sources(const Asset& asset, const std::vector<MeshInstance>& instances) {
  std::vector<VatSource> sources;
  for (const MeshInstance& inst : instances) {
    const Mesh& mesh = asset.meshes[size_t(inst.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      sources.push_back({inst.node, inst.mesh, int(p), mesh.primitives[p].vertex_count(),
                         asset.nodes[size_t(inst.node)].name, mesh.name});
    }
  }
  return sources;
}

struct VatWriter::Impl {
  Impl(std::string positions_path, std::string normals_path, std::string json_path, size_t w, size_t r,
       size_t frames)
      : positions(std::move(positions_path), w, frames * r),
        normals(std::move(normals_path), w, frames * r),
        json(std::move(json_path)) {}

  ExrImage positions, normals;
  TextFile json;
  std::vector<VatSource> sources;
  std::vector<double> times;
  double fps = 0;
  std::string clip;
  size_t vertices = 0;
  size_t width = 0;           // W: texels per row
  size_t rows_per_frame = 0;  // R
  size_t frames_written = 0;
  // One frame's rows of each image. Texel (v % W, v / W) of a frame's block is element v: the vertices lie
  // in order, followed by the zero padding of the last row, which is never written.
  std::vector<float> position_rows, normal_rows;
  float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                 std::numeric_limits<float>::infinity()};
  float hi[3] = {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                 -std::numeric_limits<float>::infinity()};
};

VatWriter::VatWriter(std::string positions_path, std::string normals_path, std::string json_path,
                     std::vector<VatSource> sources, std::vector<double> times, double fps, std::string clip_name,
                     size_t wrap) {
  assert(wrap > 0);
  const size_t vertices = total_vertices(sources);
  if (vertices == 0) throw InputError(positions_path + ": no vertices to bake into a vertex-animation texture");
  if (times.empty()) throw InputError(positions_path + ": no frames to bake into a vertex-animation texture");
  const size_t width = std::min(vertices, wrap);
  const size_t rows = (vertices + width - 1) / width;
  if (rows > size_t(INT_MAX) / times.size())
    throw InputError(positions_path + ": " + std::to_string(times.size()) + " frames of " + std::to_string(rows) +
                     " rows are too many for an EXR image");
  impl_ = std::make_unique<Impl>(std::move(positions_path), std::move(normals_path), std::move(json_path), width,
                                 rows, times.size());
  impl_->sources = std::move(sources);
  impl_->times = std::move(times);
  impl_->fps = fps;
  impl_->clip = std::move(clip_name);
  impl_->vertices = vertices;
  impl_->width = width;
  impl_->rows_per_frame = rows;
  impl_->position_rows.assign(width * rows * 4, 0.0f);
  impl_->normal_rows.assign(width * rows * 4, 0.0f);
}

VatWriter::~VatWriter() = default;

void VatWriter::append(const FrameView& frame) {
  Impl& m = *impl_;
  assert(m.frames_written < m.times.size());
  assert(frame.primitives.size() == m.sources.size());
  size_t v = 0;
  for (size_t i = 0; i < frame.primitives.size(); ++i) {
    const PrimitiveView& p = frame.primitives[i];
    assert(p.vertices == m.sources[i].vertices && p.positions.size() == p.vertices * 3);
    assert(p.normals.empty() || p.normals.size() == p.vertices * 3);
    for (size_t k = 0; k < p.vertices; ++k, ++v) {
      float* pos = &m.position_rows[v * 4];
      float* nrm = &m.normal_rows[v * 4];
      for (size_t c = 0; c < 3; ++c) {
        const float x = p.positions[k * 3 + c];
        pos[c] = x;
        m.lo[c] = std::min(m.lo[c], x);
        m.hi[c] = std::max(m.hi[c], x);
        nrm[c] = p.normals.empty() ? 0.0f : p.normals[k * 3 + c];
      }
      pos[3] = 1.0f;  // DESIGN.md: positions w = 1, normals w = 0
      nrm[3] = 0.0f;
    }
  }
  // The two images compress (ZIP) independently: one on a second thread, so a VAT-only bake uses two
  // cores.
  const size_t y = m.frames_written * m.rows_per_frame;
  std::future<void> normals = std::async(std::launch::async, [&] { m.normals.write_rows(y, m.rows_per_frame, m.normal_rows.data()); });
  m.positions.write_rows(y, m.rows_per_frame, m.position_rows.data());
  normals.get();
  ++m.frames_written;
}

std::vector<Committed> VatWriter::commit(const CommitOptions& options) {
  Impl& m = *impl_;
  if (m.frames_written != m.times.size())
    throw std::logic_error("VatWriter::commit: " + std::to_string(m.frames_written) + " of " +
                           std::to_string(m.times.size()) + " frames appended");
  m.positions.close();
  m.normals.close();

  const std::string& json_path = m.json.file().path();
  Json doc;
  doc["format"] = "dqskin vertex-animation texture";
  doc["version"] = 1;
  doc["clip"] = m.clip;
  doc["vertex_count"] = m.vertices;
  doc["frame_count"] = m.times.size();
  doc["fps"] = fps_json(m.fps);
  doc["frame_times"] = m.times;
  doc["wrap_width"] = m.width;
  doc["rows_per_frame"] = m.rows_per_frame;
  doc["width"] = m.width;
  doc["height"] = m.times.size() * m.rows_per_frame;
  doc["texel"] = "vertex v of frame f is at (v % wrap_width, f * rows_per_frame + v / wrap_width); other texels are 0";
  doc["bounds"] = {{"min", {m.lo[0], m.lo[1], m.lo[2]}}, {"max", {m.hi[0], m.hi[1], m.hi[2]}}};
  Json sources = Json::array();
  size_t first = 0;
  for (const VatSource& s : m.sources) {
    sources.push_back({{"node", s.node},
                       {"node_name", s.node_name},
                       {"mesh", s.mesh},
                       {"mesh_name", s.mesh_name},
                       {"primitive", s.primitive},
                       {"first_vertex", first},
                       {"vertex_count", s.vertices}});
    first += s.vertices;
  }
  doc["sources"] = std::move(sources);
  doc["attributes"] = {
      {"positions", {{"file", name_from(json_path, m.positions.file().path())}, {"channels", "RGBA"},
                     {"type", "float32"}, {"content", "world-space position xyz, w = 1"}}},
      {"normals", {{"file", name_from(json_path, m.normals.file().path())}, {"channels", "RGBA"},
                   {"type", "float32"}, {"content", "unit normal xyz (0 where the primitive has none), w = 0"}}}};
  m.json.write(dump(doc));

  return commit_all({&m.positions.file(), &m.normals.file(), &m.json.file()}, options);
}

std::vector<Committed> write_bone_texture(const std::string& exr_path, const std::string& json_path,
                                          const BoneTexture& texture, const Asset& asset, int skin,
                                          std::span<const double> times, double fps, const CommitOptions& options) {
  assert(skin >= 0 && size_t(skin) < asset.skins.size());
  assert(times.size() == texture.frames);
  assert(texture.rgba.size() == texture.frames * texture.width() * 4);
  const Skin& s = asset.skins[size_t(skin)];
  if (texture.width() == 0 || texture.frames == 0)
    throw InputError(exr_path + ": a bone texture needs at least one joint and one frame");

  ExrImage image(exr_path, texture.width(), texture.frames);
  TextFile json(json_path);
  image.write_all(texture.rgba.data());
  image.close();

  Json doc;
  doc["format"] = "dqskin bone texture";
  doc["version"] = 1;
  doc["skin"] = skin;
  doc["skin_name"] = s.name;
  Json names = Json::array();
  for (int j : s.joints) names.push_back(asset.nodes[size_t(j)].name);
  doc["joints"] = std::move(names);
  doc["joint_nodes"] = s.joints;
  doc["texels_per_joint"] = texture.texels_per_joint;
  doc["frame_count"] = texture.frames;
  doc["fps"] = fps_json(fps);
  doc["frame_times"] = std::vector<double>(times.begin(), times.end());
  doc["width"] = texture.width();
  doc["height"] = texture.frames;
  doc["texel"] = texture.texels_per_joint == 5
                     ? "component k of joint j at frame f is at (5 * j + k, f): k = 0 real, 1 dual (x, y, z, w; "
                       "w scalar), 2..4 rows of the scale/shear S in xyz with w = 0"
                     : "component k of joint j at frame f is at (2 * j + k, f): k = 0 real, 1 dual (x, y, z, w; "
                       "w scalar)";
  doc["file"] = name_from(json_path, exr_path);
  doc["channels"] = "RGBA";
  doc["type"] = "float32";
  json.write(dump(doc));

  return commit_all({&image.file(), &json.file()}, options);
}

}  // namespace dqskin
