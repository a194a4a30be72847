#include "vat_writer.hpp"

#include "dqskin/error.hpp"

#include <cassert>
#include <future>
#include <stdexcept>

namespace dqskin::texture {

// One image file: its AtomicFile, the writer streaming into its temporary, and the band being filled.
struct VatWriter::Image {
  Image(const std::string& path, TexelType texel_type, size_t image_width, size_t height, int image_channels)
      : file(path, false), writer(file, texel_type, image_width, height, image_channels), type(texel_type),
        width(image_width), channels(image_channels) {}

  AtomicFile file;  // synced with the rest of the bake before the manifest
  TexelFileWriter writer;
  TexelType type;
  size_t width;
  int channels;
  TexelImage band;
};

VatWriter::VatWriter(VatEncoding encoding, VatClipInfo info, const std::string& folder, VatFileNames names,
                     std::string rest_glb)
    : encoding_(std::move(encoding)), info_(std::move(info)), folder_(folder), names_(std::move(names)),
      rest_glb_(std::move(rest_glb)) {
  const VatLayout& l = encoding_.layout;
  positions_ = std::make_unique<Image>(folder_ + "/" + names_.positions, l.format.type, l.width, l.height,
                                       l.position_channels());
  if (const std::optional<TexelType> type = encoding_.normal_image_type()) {
    normals_ = std::make_unique<Image>(folder_ + "/" + names_.normals, *type, l.width, l.height, normal_channels(encoding_));
  }
}

VatWriter::~VatWriter() = default;

void VatWriter::append(const FrameView& frame) {
  const VatLayout& l = encoding_.layout;
  const size_t f = frames_written_;
  assert(f < l.frames);
  const VatLayout::Rows rows = l.frame_rows(f);
  // Frame-major layouts get a fresh band per frame; openvat fills one band, the image, over all frames.
  for (Image* image : {positions_.get(), normals_.get()}) {
    if (!image) continue;
    if (image->band.rows() != rows.count) image->band = TexelImage(image->type, image->width, rows.count, image->channels, rows.first);
    else if (l.frame_major()) image->band.reset(rows.first);
  }
  encode_vat_frame(encoding_, frame, f, positions_->band, normals_ ? &normals_->band : nullptr,
                   "clip " + info_.clip);
  ++frames_written_;
  if (!l.frame_major() && frames_written_ < l.frames) return;
  // The two images compress (ZIP) independently: the normals on a second thread.
  std::future<void> normals;
  if (normals_) normals = std::async(std::launch::async, [this] { normals_->writer.write(normals_->band); });
  positions_->writer.write(positions_->band);
  if (normals.valid()) normals.get();
}

void VatWriter::finish() {
  if (frames_written_ != encoding_.layout.frames)
    throw std::logic_error("VatWriter::finish: " + std::to_string(frames_written_) + " of " +
                           std::to_string(encoding_.layout.frames) + " frames appended");
  positions_->writer.close();
  positions_->band = TexelImage();
  if (normals_) {
    normals_->writer.close();
    normals_->band = TexelImage();
  }
}

VatWriter::WrittenImage VatWriter::positions() const { return {positions_->writer.temporary(), positions_->file.path()}; }

VatWriter::WrittenImage VatWriter::normals() const {
  if (!normals_) return {};
  return {normals_->writer.temporary(), normals_->file.path()};
}

std::vector<std::pair<std::string, Committed>> VatWriter::commit(const DecodeCheck* check, const CommitOptions& options) {
  std::vector<std::pair<std::string, AtomicFile*>> files = {{names_.positions, &positions_->file}};
  if (normals_) files.emplace_back(names_.normals, &normals_->file);
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
