#include "vat_writer.hpp"

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
        const std::string& compression, bool digest)
      : file(path, false), writer(file, texel_type, image_width, height, image_channels, compression, digest), type(texel_type),
        width(image_width), channels(image_channels) {}

  AtomicFile file;  // synced with the rest of the bake before the manifest
  TexelFileWriter writer;
  TexelType type;
  size_t width;
  int channels;
  TexelImage band;
};

VatWriter::VatWriter(VatEncoding encoding, VatClipInfo info, const std::string& folder, VatFileNames names,
                     std::string rest_glb, bool check)
    : encoding_(std::move(encoding)), info_(std::move(info)), folder_(folder), names_(std::move(names)),
      rest_glb_(std::move(rest_glb)) {
  if (check) frame_check_ = std::make_unique<VatFrameCheck>(encoding_);
  const VatLayout& l = encoding_.layout;
  const std::optional<TexelType> normal_type = encoding_.normal_image_type();
  for (size_t page = 0; page < l.pages; ++page) {
    positions_.push_back(std::make_unique<Image>(folder_ + "/" + page_file_name(names_.positions, page, l.pages),
                                                 l.format.type, l.width, l.page_height(page), l.position_channels(),
                                                 encoding_.compression, check));
    if (normal_type)
      normals_.push_back(std::make_unique<Image>(folder_ + "/" + page_file_name(names_.normals, page, l.pages),
                                                 *normal_type, l.width, l.page_height(page), normal_channels(encoding_),
                                                 encoding_.compression, check));
  }
}

VatWriter::~VatWriter() = default;

void VatWriter::append(const FrameView& frame) {
  const VatLayout& l = encoding_.layout;
  const size_t f = frames_written_;
  assert(f < l.frames);
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
  const bool write = l.frame_major() || frames_written_ == l.frames;
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

void VatWriter::finish() {
  if (frames_written_ != encoding_.layout.frames)
    throw std::logic_error("VatWriter::finish: " + std::to_string(frames_written_) + " of " +
                           std::to_string(encoding_.layout.frames) + " frames appended");
  for (auto* images : {&positions_, &normals_})
    for (const std::unique_ptr<Image>& image : *images) {
      image->writer.close();
      image->band = TexelImage();
    }
}

uint64_t VatWriter::position_digest(size_t page) const { return positions_[page]->writer.digest(); }

uint64_t VatWriter::normal_digest(size_t page) const { return normals_.empty() ? 0 : normals_[page]->writer.digest(); }

VatWriter::WrittenImage VatWriter::positions(size_t page) const {
  return {positions_[page]->writer.temporary(), positions_[page]->file.path()};
}

VatWriter::WrittenImage VatWriter::normals(size_t page) const {
  if (normals_.empty()) return {};
  return {normals_[page]->writer.temporary(), normals_[page]->file.path()};
}

std::vector<std::pair<std::string, Committed>> VatWriter::commit(const DecodeCheck* check, const CommitOptions& options,
                                                                 std::vector<DecodeCheck> clip_checks) {
  info_.clip_checks = std::move(clip_checks);
  const size_t pages = encoding_.layout.pages;
  std::vector<std::pair<std::string, AtomicFile*>> files;
  for (size_t page = 0; page < pages; ++page) {
    files.emplace_back(page_file_name(names_.positions, page, pages), &positions_[page]->file);
    if (!normals_.empty()) files.emplace_back(page_file_name(names_.normals, page, pages), &normals_[page]->file);
  }
  std::optional<AtomicFile> rest;
  if (!names_.rest_mesh.empty()) {
    rest.emplace(folder_ + "/" + names_.rest_mesh, false);
    rest->write(rest_glb_);
    files.emplace_back(names_.rest_mesh, &*rest);
  }
  std::optional<AtomicFile> side;
  if (!names_.profile_side_file.empty()) {
    side.emplace(folder_ + "/" + names_.profile_side_file, false);
    side->write(profile_side_file(encoding_, info_));
    files.emplace_back(names_.profile_side_file, &*side);
  }
  AtomicFile json(folder_ + "/" + names_.dqskin_side_file, false);
  json.write(vat_json(encoding_, info_, names_, check));
  files.emplace_back(names_.dqskin_side_file, &json);  // last: it appears only beside complete files

  if (options.overwrite == Overwrite::kRefuseDifferent)
    for (const auto& [name, file] : files)
      if (file->conflicts()) throw OutputError(file->path() + ": exists with different contents; not overwritten");
  std::vector<std::pair<std::string, Committed>> result;
  for (const auto& [name, file] : files) result.emplace_back(name, file->commit(options));
  return result;
}

}  // namespace dqskin::texture
