#include "vat_writer.hpp"

#include "exr_rows.hpp"
#include "vat_check.hpp"

#include "dqskin/error.hpp"

#include <cassert>
#include <exception>
#include <future>
#include <stdexcept>

namespace dqskin::texture {

// One image file: its AtomicFile, the writer streaming into its temporary, and the band being filled.
struct VatWriter::Image {
  Image(const std::string& path, TexelType texel_type, size_t image_width, size_t height, int image_channels,
        const std::string& compression, bool digest, TexelRows rows)
      : file(path, false), writer(file, texel_type, image_width, height, image_channels, compression, digest, rows),
        type(texel_type), width(image_width), channels(image_channels) {}

  AtomicFile file;  // synced with the rest of the bake before the manifest
  TexelFileWriter writer;
  TexelType type;
  size_t width;
  int channels;
  TexelImage band;
};

bool sliceable(const VatEncoding& e) {
  const std::optional<TexelType> normals = e.normal_image_type();
  return e.layout.frame_major() && !is_png(e.layout.format.type) && (!normals || !is_png(*normals));
}

bool slice_may_start(const VatEncoding& e, size_t f) {
  const VatLayout& l = e.layout;
  const size_t in_page = f % l.frames_per_page;
  return in_page == 0 || (in_page * l.wraps) % exr_block_rows(exr_compression(e.compression)) == 0;
}

std::string piece_file_name(const std::string& name, size_t first_row, size_t end_row) {
  return name + ".rows-" + std::to_string(first_row) + "-" + std::to_string(end_row);
}

std::string template_file_name(const std::string& name) { return name + ".template"; }

VatWriter::VatWriter(VatEncoding encoding, VatClipInfo info, const std::string& folder, VatFileNames names,
                     std::string rest_glb, bool check, VatSlice slice)
    : encoding_(std::move(encoding)), info_(std::move(info)), folder_(folder), names_(std::move(names)),
      rest_glb_(std::move(rest_glb)), slice_(slice) {
  const VatLayout& l = encoding_.layout;
  if (slice_.end == 0) slice_.end = l.frames;
  if (slice_.first >= slice_.end || slice_.end > l.frames || (!whole() && (!sliceable(encoding_) || !slice_may_start(encoding_, slice_.first))))
    throw std::logic_error("VatWriter: frames " + std::to_string(slice_.first) + " to " + std::to_string(slice_.end) +
                           " are not a slice of this texture");
  frames_written_ = slice_.first;
  if (check) frame_check_ = std::make_unique<VatFrameCheck>(encoding_);
  const std::optional<TexelType> normal_type = encoding_.normal_image_type();
  for (size_t page = 0; page < l.pages; ++page) {
    const TexelRows rows = page_rows(page);
    const bool has_rows = rows.end > rows.first;
    // A slice's images are pieces: rows of the page, under names of their own (the whole one's otherwise).
    auto name = [&](const std::string& image) {
      const std::string n = page_file_name(image, page, l.pages);
      return whole() ? n : piece_file_name(n, rows.first, rows.end);
    };
    const TexelRows file_rows = whole() ? TexelRows{} : rows;
    positions_.push_back(!has_rows ? nullptr
                                   : std::make_unique<Image>(folder_ + "/" + name(names_.positions), l.format.type, l.width,
                                                             l.page_height(page), l.position_channels(),
                                                             encoding_.compression, check, file_rows));
    if (normal_type)
      normals_.push_back(!has_rows ? nullptr
                                   : std::make_unique<Image>(folder_ + "/" + name(names_.normals), *normal_type, l.width,
                                                             l.page_height(page), normal_channels(encoding_),
                                                             encoding_.compression, check, file_rows));
  }
}

TexelRows slice_page_rows(const VatLayout& l, size_t slice_first, size_t slice_end, size_t page) {
  const size_t first = std::max(slice_first, l.page_first_frame(page));
  const size_t end = std::min(slice_end, l.page_first_frame(page) + l.page_frames(page));
  if (first >= end) return {0, 0};
  // The page's last frame takes the padding rows below it too.
  const bool last = end == l.page_first_frame(page) + l.page_frames(page);
  return {l.frame_rows(first).first, last ? l.page_height(page) : l.frame_rows(end).first};
}

TexelRows VatWriter::page_rows(size_t page) const { return slice_page_rows(encoding_.layout, slice_.first, slice_.end, page); }

VatWriter::~VatWriter() = default;

void VatWriter::append(const FrameView& frame) {
  const VatLayout& l = encoding_.layout;
  const size_t f = frames_written_;
  assert(f < slice_.end);
  const size_t page = l.page_of(f);
  Image* positions = positions_[page].get();
  Image* normals = normals_.empty() ? nullptr : normals_[page].get();
  const VatLayout::Rows rows = l.frame_rows(f);
  // Frame-major layouts get a fresh band per frame; openvat fills one band, the image, over all frames.
  for (Image* image : {positions, normals}) {
    if (!image) continue;
    if (image->band.rows() != rows.count) image->band = TexelImage(image->type, image->width, rows.count, image->channels, rows.first);
    else if (l.frame_major()) image->band.reset(rows.first);
  }
  encode_vat_frame(encoding_, frame, f, positions->band, normals ? &normals->band : nullptr, "clip " + info_.clip);
  ++frames_written_;
  const bool write = l.frame_major() || frames_written_ == slice_.end;
  // The images are handed to their files on threads of their own (each compresses on OpenEXR's pool when
  // a chunk fills) while this one checks the frame: the bands are only read meanwhile.
  std::future<void> positions_written, normals_written;
  if (write) {
    positions_written = std::async(std::launch::async, [positions] { positions->writer.write(positions->band); });
    if (normals) normals_written = std::async(std::launch::async, [normals] { normals->writer.write(normals->band); });
  }
  std::exception_ptr failed;
  try {
    if (frame_check_)
      frame_check_->frame(f, positions->band, normals ? &normals->band : nullptr, frame, positions->file.path(),
                          normals ? normals->file.path() : std::string());
  } catch (...) {
    failed = std::current_exception();
  }
  for (std::future<void>* written : {&positions_written, &normals_written})
    if (written->valid()) written->get();  // rethrows a write's error (before the check's: a full disk explains more)
  if (failed) std::rethrow_exception(failed);
}

void VatWriter::append_first(const FrameView& frame) {
  if (slice_.first > 0) encode_neighbour(frame, 0, true);
}

void VatWriter::append_next(const FrameView& frame) {
  if (slice_.end < encoding_.layout.frames) encode_neighbour(frame, slice_.end, false);
}

void VatWriter::encode_neighbour(const FrameView& frame, size_t f, bool first) {
  if (!frame_check_) return;
  const VatLayout& l = encoding_.layout;
  const VatLayout::Rows rows = l.frame_rows(f);
  const std::optional<TexelType> normal_type = encoding_.normal_image_type();
  TexelImage positions(l.format.type, l.width, rows.count, l.position_channels(), rows.first);
  TexelImage normals;
  if (normal_type) normals = TexelImage(*normal_type, l.width, rows.count, normal_channels(encoding_), rows.first);
  encode_vat_frame(encoding_, frame, f, positions, normal_type ? &normals : nullptr, "clip " + info_.clip);
  if (first) frame_check_->first_frame(positions, normal_type ? &normals : nullptr);
  else frame_check_->next_frame(f, positions, normal_type ? &normals : nullptr);
}

void VatWriter::finish() {
  if (frames_written_ != slice_.end)
    throw std::logic_error("VatWriter::finish: frames to " + std::to_string(frames_written_) + " of " +
                           std::to_string(slice_.end) + " appended");
  for (auto* images : {&positions_, &normals_})
    for (const std::unique_ptr<Image>& image : *images) {
      if (!image) continue;
      image->writer.close();
      image->band = TexelImage();
    }
}

uint64_t VatWriter::position_digest(size_t page) const { return positions_.at(page)->writer.digest(); }

uint64_t VatWriter::normal_digest(size_t page) const { return normals_.empty() ? 0 : normals_.at(page)->writer.digest(); }

VatWriter::WrittenImage VatWriter::positions(size_t page) const {
  return {positions_.at(page)->writer.temporary(), positions_.at(page)->file.path()};
}

VatWriter::WrittenImage VatWriter::normals(size_t page) const {
  if (normals_.empty()) return {};
  return {normals_.at(page)->writer.temporary(), normals_.at(page)->file.path()};
}

std::vector<std::pair<std::string, Committed>> VatWriter::commit(const DecodeCheck* check, const CommitOptions& options,
                                                                 std::vector<DecodeCheck> clip_checks) {
  info_.clip_checks = std::move(clip_checks);
  const size_t pages = encoding_.layout.pages;
  std::vector<std::pair<std::string, AtomicFile*>> files;
  auto relative = [&](const AtomicFile& file) { return file.path().substr(folder_.size() + 1); };
  for (size_t page = 0; page < pages; ++page) {
    if (!positions_[page]) continue;
    files.emplace_back(relative(positions_[page]->file), &positions_[page]->file);
    if (!normals_.empty()) files.emplace_back(relative(normals_[page]->file), &normals_[page]->file);
  }
  std::optional<AtomicFile> rest;
  if (slice_.head && !names_.rest_mesh.empty()) {
    rest.emplace(folder_ + "/" + names_.rest_mesh, false);
    rest->write(rest_glb_);
    files.emplace_back(names_.rest_mesh, &*rest);
  }
  std::optional<AtomicFile> side;
  if (slice_.head && !names_.profile_side_file.empty()) {
    side.emplace(folder_ + "/" + names_.profile_side_file, false);
    side->write(profile_side_file(encoding_, info_));
    files.emplace_back(names_.profile_side_file, &*side);
  }
  // A slice's checked texture: vat.json without the figures, which only the merge has all of.
  const bool to_fill = !whole() && frame_check_;
  const std::string json_name = to_fill ? template_file_name(names_.dqskin_side_file) : names_.dqskin_side_file;
  std::optional<AtomicFile> json;
  if (slice_.head) {
    json.emplace(folder_ + "/" + json_name, false);
    json->write(vat_json(encoding_, info_, names_, to_fill ? nullptr : check));
    files.emplace_back(json_name, &*json);  // last: it appears only beside complete files
  }

  if (options.overwrite == Overwrite::kRefuseDifferent)
    for (const auto& [name, file] : files)
      if (file->conflicts()) throw OutputError(file->path() + ": exists with different contents; not overwritten");
  std::vector<std::pair<std::string, Committed>> result;
  for (const auto& [name, file] : files) result.emplace_back(name, file->commit(options));
  return result;
}

}  // namespace dqskin::texture
