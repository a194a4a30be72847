#include "vat_check.hpp"

#include "dqskin/error.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <future>
#include <cmath>
#include <numbers>
#include <stdexcept>

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

nlohmann::json ErrorHistogram::to_json() const {
  nlohmann::json bins = nlohmann::json::array();
  for (size_t i = 0; i < bins_.size(); ++i)
    if (bins_[i]) bins.push_back({i, bins_[i]});
  return {{"max", max_}, {"count", count_}, {"bins", std::move(bins)}};
}

ErrorHistogram ErrorHistogram::from_json(const nlohmann::json& j, const std::string& what) {
  ErrorHistogram h;
  try {
    h.max_ = j.at("max").get<double>();
    h.count_ = j.at("count").get<size_t>();
    size_t sum = 0;
    if (!j.at("count").is_number_unsigned()) throw InputError("the count is not a whole number");
    for (const nlohmann::json& bin : j.at("bins")) {
      if (!bin.is_array() || bin.size() != 2 || !bin[0].is_number_unsigned() || !bin[1].is_number_unsigned())
        throw InputError("a bin is not [index, count]");
      const size_t i = bin[0].get<size_t>(), n = bin[1].get<size_t>();
      if (i >= h.bins_.size()) throw InputError("a bin past the last");
      if (n > h.count_ - sum) throw InputError("the bins add up to more than the count");
      h.bins_[i] += n;
      sum += n;
    }
    if (sum != h.count_ || !(h.max_ >= 0)) throw InputError("the bins do not add up to the count");
  } catch (const std::exception& e) {
    throw InputError(what + ": not an error histogram (" + e.what() + ")");
  }
  return h;
}

namespace {

// Adds the distance of every decoded position to the reference's to `errors`, and lowers `min_cosine` to
// the smallest cosine between decoded and reference normals: the largest angle is its arc cosine, taken
// once (acos is correctly rounded, so monotonic: the same figure as the largest of every arc cosine).
void compare(const std::vector<float>& positions, const std::vector<float>& normals, const FrameView& reference,
             ErrorHistogram& errors, double& min_cosine) {
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
      min_cosine = std::min(min_cosine, std::clamp(glm::dot(n, m) / (ln * lm), -1.0, 1.0));
    }
  }
}

// The largest distance of a vertex of `positions` (3 floats per vertex, or the reference's when null)
// from its place in `first`.
double motion(const std::vector<float>& first, const std::vector<float>* positions, const FrameView& reference) {
  double most = 0;
  size_t v = 0;
  for (const PrimitiveView& p : reference.primitives)
    for (size_t k = 0; k < p.vertices; ++k, ++v) {
      const glm::dvec3 from(first[3 * v], first[3 * v + 1], first[3 * v + 2]);
      const glm::dvec3 at = positions ? glm::dvec3((*positions)[3 * v], (*positions)[3 * v + 1], (*positions)[3 * v + 2])
                                      : glm::dvec3(p.positions[3 * k], p.positions[3 * k + 1], p.positions[3 * k + 2]);
      most = std::max(most, glm::length(at - from));
    }
  return most;
}

double degrees(double cosine) { return std::acos(cosine) * 180 / std::numbers::pi; }

}  // namespace

void VatFrameCheck::set_clip_starts(std::vector<size_t> first_frames) {
  if (first_frames.empty() || first_frames[0] != 0 || !std::is_sorted(first_frames.begin(), first_frames.end()))
    throw std::logic_error("VatFrameCheck::set_clip_starts: clips must start at 0 and in order");
  clips_.assign(first_frames.size(), Clip());
  for (size_t c = 0; c < first_frames.size(); ++c) clips_[c].first_frame = first_frames[c];
}

size_t VatFrameCheck::clip_of(size_t f) const {
  const auto after = std::upper_bound(clips_.begin(), clips_.end(), f,
                                      [](size_t frame, const Clip& c) { return frame < c.first_frame; });
  return size_t(after - clips_.begin()) - 1;
}

void VatFrameCheck::frame(size_t f, const TexelImage& positions, const TexelImage* normals, const FrameView& reference,
                          const std::string& positions_name, const std::string& normals_name) {
  // Finite texels: the encoder refuses non-finite values, so this guards the encoder itself. Openvat's band
  // is the whole image, filled frame by frame: it is scanned once, when its last frame is in.
  const bool scan = e_.layout.frame_major() || f + 1 == e_.layout.frames;
  if (scan) {
    if (const std::string at = positions.first_non_finite(); !at.empty())
      throw OutputError(positions_name + ": texel " + at + " is not finite");
    if (normals)
      if (const std::string at = normals->first_non_finite(); !at.empty())
        throw OutputError(normals_name + ": texel " + at + " is not finite");
  }
  decode_vat_frame(e_, positions, normals, f, positions_, normals_);
  Clip& c = clips_[clip_of(f)];
  compare(positions_, normals_, reference, c.errors, c.min_cosine);
  if (c.first_positions.empty()) {
    c.first_positions = positions_;
    return;
  }
  c.decoded_motion = std::max(c.decoded_motion, motion(c.first_positions, &positions_, reference));
  c.reference_motion = std::max(c.reference_motion, motion(c.first_positions, nullptr, reference));
}

void VatFrameCheck::first_frame(const TexelImage& positions, const TexelImage* normals) {
  std::vector<float> unused;
  decode_vat_frame(e_, positions, normals, 0, clips_[0].first_positions, unused);
}

void VatFrameCheck::next_frame(size_t f, const TexelImage& positions, const TexelImage* normals) {
  decode_vat_frame(e_, positions, normals, f, next_.positions, next_.normals);
  next_.frame = f;
}

void DecodeShare::merge(const DecodeShare& other) {
  frames.merge(other.frames);
  midpoints.merge(other.midpoints);
  max_normal_degrees = std::max(max_normal_degrees, other.max_normal_degrees);
  max_midpoint_normal_degrees = std::max(max_midpoint_normal_degrees, other.max_midpoint_normal_degrees);
}

DecodeCheck DecodeShare::figures() const {
  DecodeCheck c;
  c.max_error = frames.max();
  c.p99_error = frames.quantile(0.99);
  c.max_midpoint_error = midpoints.max();
  c.p99_midpoint_error = midpoints.quantile(0.99);
  c.max_normal_degrees = max_normal_degrees;
  c.max_midpoint_normal_degrees = max_midpoint_normal_degrees;
  c.samples = frames.count() + midpoints.count();
  return c;
}

nlohmann::json DecodeShare::to_json() const {
  return {{"frames", frames.to_json()},
          {"midpoints", midpoints.to_json()},
          {"max_normal_degrees", max_normal_degrees},
          {"max_midpoint_normal_degrees", max_midpoint_normal_degrees}};
}

DecodeShare DecodeShare::from_json(const nlohmann::json& j, const std::string& what) {
  DecodeShare s;
  if (!j.is_object()) throw InputError(what + ": not a decode-check share");
  s.frames = ErrorHistogram::from_json(j.value("frames", nlohmann::json()), what + ".frames");
  s.midpoints = ErrorHistogram::from_json(j.value("midpoints", nlohmann::json()), what + ".midpoints");
  try {
    s.max_normal_degrees = j.at("max_normal_degrees").get<double>();
    s.max_midpoint_normal_degrees = j.at("max_midpoint_normal_degrees").get<double>();
  } catch (const std::exception& e) {
    throw InputError(what + ": " + e.what());
  }
  return s;
}

VatDecodeChecker::VatDecodeChecker(const VatWriter& writer)
    : writer_(writer), e_(writer.encoding()),
      frames_(writer.frame_check() ? *writer.frame_check()
                                   : throw std::logic_error("VatDecodeChecker: the writer did not check its frames")),
      pages_verified_(writer.encoding().layout.pages, false), midpoints_(frames_.clips()) {
  // Pages the slice has no rows in are not this writer's to verify.
  for (size_t page = 0; page < pages_verified_.size(); ++page)
    if (writer.page_rows(page).end == 0) pages_verified_[page] = true;
  open_page(e_.layout.page_of(writer.slice().first));
}

VatDecodeChecker::~VatDecodeChecker() = default;

void VatDecodeChecker::open_page(size_t page) {
  if (page == page_) return;
  if (page_ != SIZE_MAX && !pages_verified_[page_]) finish_page();
  const VatLayout& l = e_.layout;
  const VatWriter::WrittenImage positions = writer_.positions(page), normals = writer_.normals(page);
  positions_name_ = positions.name;
  normals_name_ = normals.name;
  rows_ = writer_.page_rows(page);
  const TexelRows file_rows = rows_.first == 0 && rows_.end == l.page_height(page) ? TexelRows{} : rows_;
  positions_ = std::make_unique<TexelFileReader>(positions.temporary, positions.name, l.format.type, l.width,
                                                 l.page_height(page), l.position_channels(), file_rows);
  normals_.reset();
  if (const std::optional<TexelType> type = e_.normal_image_type())
    normals_ = std::make_unique<TexelFileReader>(normals.temporary, normals.name, *type, l.width, l.page_height(page),
                                                 normal_channels(e_), file_rows);
  page_ = page;
  band_read_ = false;
  digested_rows_ = rows_.first;
  position_digest_ = TexelDigest();
  normal_digest_ = TexelDigest();
}

void VatDecodeChecker::read_rows(size_t first, size_t count) {
  if (first > digested_rows_) read_rows(digested_rows_, first - digested_rows_);  // the rows between, digested
  // Positions and normals are read at once, on two threads (OpenEXR decompresses a read's blocks on its pool).
  std::future<void> normals;
  if (normals_) normals = std::async(std::launch::async, [&] { normals_->read(first, count, normal_band_); });
  positions_->read(first, count, position_band_);
  if (normals.valid()) normals.get();
  band_read_ = true;
  if (first + count <= digested_rows_) return;
  const size_t skip = digested_rows_ - first;
  auto digest = [&](const TexelImage& band, TexelDigest& d) {
    const size_t row_bytes = band.width() * size_t(band.channels()) * channel_bytes(band.type());
    d.add(band.data() + skip * row_bytes, (count - skip) * row_bytes);
  };
  digest(position_band_, position_digest_);
  if (normals_) digest(normal_band_, normal_digest_);
  digested_rows_ = first + count;
}

void VatDecodeChecker::finish_page() {
  const size_t height = rows_.end;
  const size_t rows = std::max<size_t>(256, position_band_.rows());
  while (digested_rows_ < height) read_rows(digested_rows_, std::min(rows, height - digested_rows_));
  band_read_ = false;
  const std::string differs = ": the texels read back differ from those the check compared (changed after writing?)";
  if (position_digest_.value() != writer_.position_digest(page_)) throw OutputError(positions_name_ + differs);
  if (normals_ && normal_digest_.value() != writer_.normal_digest(page_)) throw OutputError(normals_name_ + differs);
  pages_verified_[page_] = true;
}

const VatDecodeChecker::Decoded& VatDecodeChecker::decode(size_t f) {
  for (const Decoded* d : std::initializer_list<const Decoded*>{&current_, &next_, &frames_.next()})
    if (d->frame == f) return *d;
  if (f < writer_.slice().first || f >= writer_.slice().end)
    throw std::logic_error("VatDecodeChecker: frame " + std::to_string(f) + " is not the slice's");
  const VatLayout& l = e_.layout;
  open_page(l.page_of(f));
  // Frame-major layouts read bands of whole frames, at least 256 rows and 8 MiB (many EXR blocks of 16 or
  // 32 rows, each decompressed once, not once per frame that shares it, and enough for every core);
  // openvat's frames lie in every wrap: the image, read once.
  const VatLayout::Rows rows = l.frame_rows(f);
  const bool in_band = band_read_ && rows.first >= position_band_.first_row() &&
                       rows.first + rows.count <= position_band_.first_row() + position_band_.rows();
  if (!in_band) {
    size_t first = rows.first, count = rows.count;
    if (l.frame_major()) {
      const size_t height = rows_.end;
      const size_t row_bytes = l.width * size_t(l.position_channels()) * channel_bytes(l.format.type);
      const size_t band_rows = std::max<size_t>(256, (size_t(8) << 20) / row_bytes);
      const size_t frames = std::max<size_t>(1, band_rows / rows.count);
      count = std::min(height - first, frames * rows.count);
    }
    read_rows(first, count);
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
  const size_t c = frames_.clip_of(f);
  Midpoints& m = midpoints_[c];
  compare(positions, normals, reference, m.errors, m.min_cosine);
  if (!frames_.clip(c).first_positions.empty())
    m.reference_motion = std::max(m.reference_motion, motion(frames_.clip(c).first_positions, nullptr, reference));
}

DecodeCheck VatDecodeChecker::finish() {
  for (size_t page = 0; page < pages_verified_.size(); ++page) {
    if (pages_verified_[page]) continue;
    open_page(page);
    finish_page();
  }
  ErrorHistogram frames, midpoints;
  double min_cosine = 1, midpoint_min_cosine = 1;
  for (size_t c = 0; c < midpoints_.size(); ++c) {
    frames.merge(frames_.clip(c).errors);
    midpoints.merge(midpoints_[c].errors);
    min_cosine = std::min(min_cosine, frames_.clip(c).min_cosine);
    midpoint_min_cosine = std::min(midpoint_min_cosine, midpoints_[c].min_cosine);
  }
  DecodeCheck c;
  c.max_error = frames.max();
  c.p99_error = frames.quantile(0.99);
  c.max_midpoint_error = midpoints.max();
  c.p99_midpoint_error = midpoints.quantile(0.99);
  c.max_normal_degrees = degrees(min_cosine);
  c.max_midpoint_normal_degrees = degrees(midpoint_min_cosine);
  c.samples = frames.count() + midpoints.count();
  return c;
}

DecodeShare VatDecodeChecker::share() const {
  DecodeShare s;
  for (size_t c = 0; c < midpoints_.size(); ++c) {
    s.frames.merge(frames_.clip(c).errors);
    s.midpoints.merge(midpoints_[c].errors);
  }
  const DecodeCheck whole = midpoints_.size() == 1 ? clip_result(0) : DecodeCheck();
  s.max_normal_degrees = whole.max_normal_degrees;
  s.max_midpoint_normal_degrees = whole.max_midpoint_normal_degrees;
  return s;
}

DecodeCheck VatDecodeChecker::clip_result(size_t c) const {
  const VatFrameCheck::Clip& f = frames_.clip(c);
  const Midpoints& m = midpoints_[c];
  DecodeCheck r;
  r.max_error = f.errors.max();
  r.p99_error = f.errors.quantile(0.99);
  r.max_midpoint_error = m.errors.max();
  r.p99_midpoint_error = m.errors.quantile(0.99);
  r.max_normal_degrees = degrees(f.min_cosine);
  r.max_midpoint_normal_degrees = degrees(m.min_cosine);
  r.samples = f.errors.count() + m.errors.count();
  return r;
}

double VatDecodeChecker::reference_motion(size_t c) const {
  return std::max(frames_.clip(c).reference_motion, midpoints_[c].reference_motion);
}

double VatDecodeChecker::decoded_motion(size_t c) const { return frames_.clip(c).decoded_motion; }

}  // namespace dqskin::texture
