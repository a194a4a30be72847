#include "vat_check.hpp"

#include "dqskin/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <future>
#include <cmath>
#include <numbers>

namespace dqskin::texture {

void ErrorHistogram::add(double error) {
  ++count_;
  max_ = std::max(max_, error);
  if (!(error > 0)) {
    ++bins_[0];
    return;
  }
  const double position = (std::log10(error) - kFirstDecade) * kPerDecade;
  const size_t bin = position < 0 ? 1 : std::min(bins_.size() - 1, size_t(position) + 1);
  ++bins_[bin];
}

void ErrorHistogram::merge(const ErrorHistogram& other) {
  for (size_t i = 0; i < bins_.size(); ++i) bins_[i] += other.bins_[i];
  max_ = std::max(max_, other.max_);
  count_ += other.count_;
}

double ErrorHistogram::quantile(double q) const {
  if (count_ == 0) return 0;
  const double wanted = q * double(count_);
  size_t seen = 0;
  for (size_t i = 0; i < bins_.size(); ++i) {
    seen += bins_[i];
    if (double(seen) >= wanted) {
      if (i == 0) return 0;
      const double upper = std::pow(10.0, kFirstDecade + double(i) / kPerDecade);  // bin i's upper edge
      return std::min(upper, max_);
    }
  }
  return max_;
}

VatDecodeChecker::VatDecodeChecker(const VatWriter& writer) : writer_(writer), e_(writer.encoding()) { open_page(0); }

void VatDecodeChecker::open_page(size_t page) {
  if (page == page_) return;
  const VatLayout& l = e_.layout;
  const VatWriter::WrittenImage positions = writer_.positions(page), normals = writer_.normals(page);
  positions_name_ = positions.name;
  normals_name_ = normals.name;
  positions_ = std::make_unique<TexelFileReader>(positions.temporary, positions.name, l.format.type, l.width,
                                                 l.page_height(page), l.position_channels());
  normals_.reset();
  if (const std::optional<TexelType> type = e_.normal_image_type())
    normals_ = std::make_unique<TexelFileReader>(normals.temporary, normals.name, *type, l.width, l.page_height(page),
                                                 normal_channels(e_));
  page_ = page;
  whole_read_ = false;
}

VatDecodeChecker::~VatDecodeChecker() = default;

const VatDecodeChecker::Decoded& VatDecodeChecker::decode(size_t f) {
  for (const Decoded* d : {&current_, &next_})
    if (d->frame == f) return *d;
  const VatLayout& l = e_.layout;
  open_page(l.page_of(f));
  // Frame-major layouts read bands of whole frames, at least 256 rows (several EXR blocks of 16 or 32
  // rows, each decompressed once, not once per frame that shares it); openvat's frames lie in every wrap:
  // the image, read once. Positions and normals are read at once, on two threads.
  const VatLayout::Rows rows = l.frame_rows(f);
  const bool in_band = whole_read_ && rows.first >= position_band_.first_row() &&
                       rows.first + rows.count <= position_band_.first_row() + position_band_.rows();
  if (!in_band) {
    size_t first = rows.first, count = rows.count;
    if (l.frame_major()) {
      const size_t height = l.page_height(l.page_of(f));
      const size_t frames = std::max<size_t>(1, 256 / rows.count);
      count = std::min(height - first, frames * rows.count);
    }
    std::future<void> normals;
    if (normals_) normals = std::async(std::launch::async, [&] { normals_->read(first, count, normal_band_); });
    positions_->read(first, count, position_band_);
    if (normals.valid()) normals.get();
    if (const std::string at = position_band_.first_non_finite(); !at.empty())
      throw OutputError(positions_name_ + ": texel " + at + " is not finite");
    if (normals_)
      if (const std::string at = normal_band_.first_non_finite(); !at.empty())
        throw OutputError(normals_name_ + ": texel " + at + " is not finite");
    whole_read_ = true;
  }
  // Overwrite the slot holding no frame, else the earlier frame (callers copy what they still need).
  auto older = [](const Decoded& a, const Decoded& b) {
    return a.frame == SIZE_MAX || (b.frame != SIZE_MAX && a.frame < b.frame);
  };
  Decoded& slot = older(current_, next_) ? current_ : next_;
  decode_vat_frame(e_, position_band_, normals_ ? &normal_band_ : nullptr, f, slot.positions, slot.normals);
  slot.frame = f;
  return slot;
}

void VatDecodeChecker::compare(const std::vector<float>& positions, const std::vector<float>& normals,
                               const FrameView& reference, ErrorHistogram& errors, double& normal_degrees) {
  size_t v = 0;
  for (const PrimitiveView& p : reference.primitives) {
    for (size_t k = 0; k < p.vertices; ++k, ++v) {
      const glm::dvec3 want(p.positions[3 * k], p.positions[3 * k + 1], p.positions[3 * k + 2]);
      const glm::dvec3 got(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
      errors.add(glm::length(got - want));
      if (normals.empty() || p.normals.empty()) continue;
      const glm::dvec3 n(p.normals[3 * k], p.normals[3 * k + 1], p.normals[3 * k + 2]);
      const glm::dvec3 m(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
      const double ln = glm::length(n), lm = glm::length(m);
      if (!(ln > 0) || !(lm > 0)) continue;
      const double c = std::clamp(glm::dot(n, m) / (ln * lm), -1.0, 1.0);
      normal_degrees = std::max(normal_degrees, std::acos(c) * 180 / std::numbers::pi);
    }
  }
}

void VatDecodeChecker::baked_frame(size_t f, const FrameView& reference) {
  const Decoded& d = decode(f);
  compare(d.positions, d.normals, reference, frame_errors_, max_normal_degrees_);
  if (first_positions_.empty()) {
    first_positions_ = d.positions;
    return;
  }
  // Motion: the largest distance of any vertex from its place in frame 0, decoded and deformed.
  size_t v = 0;
  for (const PrimitiveView& p : reference.primitives) {
    for (size_t k = 0; k < p.vertices; ++k, ++v) {
      const glm::dvec3 first(first_positions_[3 * v], first_positions_[3 * v + 1], first_positions_[3 * v + 2]);
      const glm::dvec3 decoded(d.positions[3 * v], d.positions[3 * v + 1], d.positions[3 * v + 2]);
      const glm::dvec3 want(p.positions[3 * k], p.positions[3 * k + 1], p.positions[3 * k + 2]);
      decoded_motion_ = std::max(decoded_motion_, glm::length(decoded - first));
      reference_motion_ = std::max(reference_motion_, glm::length(want - first));
    }
  }
}

void VatDecodeChecker::midpoint(size_t f, const FrameView& reference) {
  const Decoded& a = decode(f);
  std::vector<float> positions = a.positions, normals = a.normals;
  const Decoded& b = decode(f + 1);
  // A runtime's linear interpolation, in float: (a + b) / 2; normals renormalized.
  for (size_t i = 0; i < positions.size(); ++i) positions[i] = positions[i] + (b.positions[i] - positions[i]) * 0.5f;
  for (size_t i = 0; i + 2 < normals.size(); i += 3) {
    glm::vec3 n(normals[i] + b.normals[i], normals[i + 1] + b.normals[i + 1], normals[i + 2] + b.normals[i + 2]);
    const float l = glm::length(n);
    if (l > 0) n /= l;
    for (int c = 0; c < 3; ++c) normals[i + size_t(c)] = n[c];
  }
  compare(positions, normals, reference, midpoint_errors_, max_midpoint_normal_degrees_);
}

DecodeCheck VatDecodeChecker::result() const {
  DecodeCheck c;
  c.max_error = frame_errors_.max();
  c.p99_error = frame_errors_.quantile(0.99);
  c.max_midpoint_error = midpoint_errors_.max();
  c.p99_midpoint_error = midpoint_errors_.quantile(0.99);
  c.max_normal_degrees = max_normal_degrees_;
  c.max_midpoint_normal_degrees = max_midpoint_normal_degrees_;
  c.samples = frame_errors_.count() + midpoint_errors_.count();
  return c;
}

}  // namespace dqskin::texture
