#include "vat_side_files.hpp"

#include "texel_image.hpp"

#include "dqskin/error.hpp"

#include <cmath>

namespace dqskin::texture {

using Json = nlohmann::ordered_json;  // keys in the order written, for people reading the files

namespace {

Json vec(const glm::dvec3& v) { return Json::array({v.x, v.y, v.z}); }
Json box_json(const Box& b) { return {{"min", vec(b.lo)}, {"max", vec(b.hi)}}; }
std::string dump(const Json& j, int indent) { return j.dump(indent, ' ', false, Json::error_handler_t::replace) + "\n"; }

// Where vertex v of frame f is, in words, per profile.
std::string texel_formula(const VatLayout& l) {
  switch (l.format.profile) {
    case VatProfile::kDqskin:
    case VatProfile::kHoudini:
      if (l.pages > 1)
        return "vertex v of frame f is in page floor(f / frames_per_page) at (v % wrap_width, (f % frames_per_page) * "
               "rows_per_frame + floor(v / wrap_width)), row 0 the first of the file; other texels are 0";
      return "vertex v of frame f is at (v % wrap_width, f * rows_per_frame + floor(v / wrap_width)), row 0 the "
             "first of the file; other texels are 0";
    case VatProfile::kOpenVat:
      return std::string("vertex v of frame f is at (v % wrap_width, floor(v / wrap_width) * frame_count + f), row 0 "
                         "the first of the file") +
             (l.format.normals == NormalMode::kPacked ? "; its normal at the same column, height / 2 rows lower" : "") +
             "; other texels are 0";
  }
  return {};
}

std::string position_formula(const VatEncoding& e) {
  const bool unorm = is_png(e.layout.format.type);
  const std::string t = unorm ? "texel.rgb / " + std::to_string(unorm_max(e.layout.format.type)) : "texel.rgb";
  switch (e.layout.format.profile) {
    case VatProfile::kDqskin:
      return unorm ? "position = remap.min + " + t + " * (remap.max - remap.min)" : "position = texel.xyz";
    case VatProfile::kOpenVat:
      return "position = rest + blender_to_gltf(Min + " + t +
             " * (Max - Min)), blender_to_gltf(v) = (v.x, v.z, -v.y); rest = the rest mesh's POSITION";
    case VatProfile::kHoudini:
      return unorm ? "position = rest + Bound Min + " + t + " * (Bound Max - Bound Min); rest = the rest mesh (the clip's first frame)"
                   : "position = rest + texel.rgb; rest = the rest mesh (the clip's first frame)";
  }
  return {};
}

std::string normal_formula(const VatEncoding& e) {
  const VatFormat& f = e.layout.format;
  const bool unorm = is_png(f.type);
  const std::string scale = unorm ? " / " + std::to_string(unorm_max(f.type)) : "";
  switch (f.normals) {
    case NormalMode::kNone: return "none";
    case NormalMode::kOct8:
    case NormalMode::kOct16:
      return "normal = octahedral_decode(texel.rg / " + std::to_string(f.normals == NormalMode::kOct8 ? 255 : 65535) +
             " * 2 - 1): n = (u, v, 1 - |u| - |v|); if n.z < 0, n.xy = (1 - |n.yx|) * sign(n.xy); normalize";
    case NormalMode::kSeparate:
    case NormalMode::kPacked: break;
  }
  switch (f.profile) {
    case VatProfile::kDqskin:
      return unorm ? "normal = normalize(texel.rgb" + scale + " * 2 - 1)" : "normal = texel.xyz";
    case VatProfile::kOpenVat:
      return "normal = normalize(blender_to_gltf(texel.rgb" + scale + " * 2 - 1))";
    case VatProfile::kHoudini:
      if (f.normals == NormalMode::kPacked)
        return "a = texel.a * 1024; x = floor(a / 32) / 31.5; y = (a - floor(a / 32) * 32) / 31.5; v = (x, y) * 4 - 2; "
               "d = dot(v, v); xy = v * sqrt(1 - d / 4); normal = normalize((xy.x, 1 - d / 2, xy.y))";
      return "q = texel" + scale + (unorm ? " * 2 - 1" : "") +
             "; normal = normalize(rotate(q, (0, 1, 0))), rotate(q, v) = v + 2 cross(q.xyz, cross(q.xyz, v) + q.w v)";
  }
  return {};
}

// How version 1 named texel types.
const char* type_name(TexelType type) {
  switch (type) {
    case TexelType::kFloat32: return "float32";
    case TexelType::kHalf: return "float16";
    case TexelType::kUnorm16: return "uint16";
    case TexelType::kUnorm8: return "uint8";
  }
  return "?";
}

const char* axes(VatProfile profile) {
  return profile == VatProfile::kOpenVat
             ? "Blender's: right-handed, +z up; stored (x, y, z) = glTF (x, -z, y); metres"
             : "glTF's: right-handed, +y up, metres";
}

// The clip table; one clip of every frame when the info names none (a writer's caller that bakes one clip).
std::vector<VatClipEntry> clip_table(const VatClipInfo& info, const VatLayout& l) {
  if (!info.clips.empty()) return info.clips;
  const double duration = info.times.empty() ? 0 : info.times.back() - info.times.front();
  return {{info.clip, 0, l.frames, info.fps, duration, info.loops}};
}

double round_out(double x, double step, bool up) { return (up ? std::ceil(x / step) : std::floor(x / step)) * step; }

}  // namespace

VatFileNames vat_file_names(const VatFormat& format, const std::string& asset) {
  const std::string ext = file_extension(format.type);
  VatFileNames n;
  const bool separate = format.normals != NormalMode::kNone && format.normals != NormalMode::kPacked;
  const std::string normal_ext = format.normals == NormalMode::kOct8 || format.normals == NormalMode::kOct16 ? "png" : ext;
  switch (format.profile) {
    case VatProfile::kDqskin:
      n.positions = "vat_positions." + ext;
      if (separate) n.normals = "vat_normals." + normal_ext;
      n.rest_mesh = "rest.glb";
      break;
    case VatProfile::kOpenVat:
      n.positions = asset + "_vat." + ext;
      if (separate) n.normals = asset + "_vnrm." + ext;
      n.rest_mesh = asset + ".glb";
      n.profile_side_file = asset + "-remap_info.json";
      break;
    case VatProfile::kHoudini:
      n.positions = asset + "_pos." + ext;
      if (separate) n.normals = asset + "_rot." + ext;
      n.rest_mesh = asset + "_mesh.glb";
      n.profile_side_file = asset + "_data.json";
      break;
  }
  return n;
}

Json DecodeCheck::to_json() const {
  return {{"max_error", max_error},
          {"p99_error", p99_error},
          {"max_midpoint_error", max_midpoint_error},
          {"p99_midpoint_error", p99_midpoint_error},
          {"max_normal_degrees", max_normal_degrees},
          {"max_midpoint_normal_degrees", max_midpoint_normal_degrees},
          {"samples", samples}};
}

Box decimal_bounds(const Box& box) {
  if (box.empty()) return box;
  const glm::dvec3 range = box.hi - box.lo;
  // The grid follows the widest side (the precision that matters); a box of no extent follows its place.
  double widest = std::max({range.x, range.y, range.z});
  if (!(widest > 0))
    widest = std::max({std::abs(box.lo.x), std::abs(box.lo.y), std::abs(box.lo.z), std::abs(box.hi.x),
                       std::abs(box.hi.y), std::abs(box.hi.z)});
  if (!(widest > 0)) return box;
  // k · 10^e computed as k / 10^−e (or k · 10^e): both operands exact, so the result is the double nearest
  // the decimal, the value any JSON reader gets back.
  const int e = int(std::floor(std::log10(widest))) - 3;
  const double scale = std::pow(10.0, std::abs(e));
  auto decimal = [&](double x, bool up) {
    const double k = e < 0 ? x * scale : x / scale;
    const double r = up ? std::ceil(k) : std::floor(k);
    return e < 0 ? r / scale : r * scale;
  };
  Box out;
  for (int c = 0; c < 3; ++c) {
    out.lo[c] = decimal(box.lo[c], false);
    out.hi[c] = decimal(box.hi[c], true);
    // x · scale may round across an integer: keep the data inside whatever happened.
    if (out.lo[c] > box.lo[c]) out.lo[c] = decimal(box.lo[c] - std::pow(10.0, e), false);
    if (out.hi[c] < box.hi[c]) out.hi[c] = decimal(box.hi[c] + std::pow(10.0, e), true);
  }
  return out;
}

Box houdini_encoded_bounds(const Box& clip_bounds, const VatLayout& l, const std::string& what) {
  const size_t rows = l.wraps;
  if (rows > 899)
    throw InputError(what + ": " + std::to_string(rows) +
                     " rows per frame; Houdini's VAT 3 bounds encode at most 899 (use a wider --max-size)");
  Box b;
  for (int c = 0; c < 3; ++c) {
    b.lo[c] = round_out(clip_bounds.lo[c], 0.1, false);
    b.hi[c] = round_out(clip_bounds.hi[c], 0.1, true);
  }
  const bool hdr = !is_png(l.format.type);
  const double code = (hdr ? 0.5 : 0.0) + 0.01 * double(rows / 100);  // one position texture
  b.hi.z += code * 0.1;
  b.lo.y -= double(rows % 100) * 0.001;
  const double rx = double(l.used_width) / double(l.width), ry = double(l.used_height) / double(l.height);
  b.lo.z -= (1 - rx) * 0.1;
  b.lo.x -= (1 - ry) * 0.1;
  return b;
}

std::string with_decode_check(const std::string& json_text, const DecodeCheck& check, const std::string& what) {
  Json doc = Json::parse(json_text, nullptr, false);
  if (!doc.is_object()) throw InputError(what + ": not a JSON object");
  doc["decode_check"] = check.to_json();
  return dump(doc, 2);
}

std::string vat_json(const VatEncoding& e, const VatClipInfo& info, const VatFileNames& names, const DecodeCheck* check) {
  const VatLayout& l = e.layout;
  Json doc;
  doc["format"] = "dqskin vertex-animation texture";
  doc["version"] = 2;
  doc["profile"] = to_string(l.format.profile);
  doc["encoding"] = to_string(l.format.type);
  doc["normals"] = to_string(l.format.normals);
  if (!is_png(l.format.type)) doc["exr_compression"] = exr_compression(e.compression);
  doc["clip"] = info.clips.size() > 1 ? Json(nullptr) : Json(info.clip);
  doc["vertex_count"] = l.vertices;
  doc["frame_count"] = l.frames;
  doc["fps"] = info.fps > 0 ? Json(info.fps) : Json(nullptr);
  doc["frame_times"] = info.times;
  // The clip table (docs/DESIGN.md §4.9): where each clip's frames are. Frame-major layouts hold a clip in
  // consecutive rows (of the page its first frame is in, when paged); openvat's frames lie in every wrap,
  // so a clip's rows are given in the first wrap.
  Json clips = Json::array();
  const std::vector<VatClipEntry> entries = clip_table(info, l);
  for (size_t i = 0; i < entries.size(); ++i) {
    const VatClipEntry& c = entries[i];
    Json entry = {{"name", c.name}};
    if (l.pages > 1) entry["first_page"] = l.page_of(c.first_frame);
    if (l.frame_major()) {
      entry["first_row"] = (c.first_frame - l.page_first_frame(l.page_of(c.first_frame))) * l.wraps;
      entry["row_count"] = c.frame_count * l.wraps;
    } else {
      entry["first_row"] = c.first_frame;
      entry["row_count"] = c.frame_count;
    }
    entry["first_frame"] = c.first_frame;
    entry["frame_count"] = c.frame_count;
    entry["fps"] = c.fps > 0 ? Json(c.fps) : Json(nullptr);
    entry["duration"] = c.duration;
    entry["loop"] = c.loops;
    // The animated mesh over the clip's frames, for culling and framing one clip of several.
    Box bounds;
    for (size_t f = c.first_frame; f < c.first_frame + c.frame_count && f < info.frame_bounds.size(); ++f)
      bounds.add(info.frame_bounds[f]);
    entry["bounds"] = box_json(bounds);
    if (i < info.clip_checks.size()) entry["decode_check"] = info.clip_checks[i].to_json();
    clips.push_back(std::move(entry));
  }
  doc["clips"] = std::move(clips);
  doc["wrap_width"] = l.wrap;
  doc["rows_per_frame"] = l.format.profile == VatProfile::kOpenVat ? 1 : l.wraps;
  if (l.format.profile == VatProfile::kOpenVat) doc["wraps"] = l.wraps;
  doc["pages"] = l.pages;
  if (l.pages > 1) {
    // Frame f is in page floor(f / frames_per_page), as frame f % frames_per_page of that page's images.
    Json table = Json::array();
    for (size_t p = 0; p < l.pages; ++p) {
      Json page = {{"positions", page_file_name(names.positions, p, l.pages)}};
      if (!names.normals.empty()) page["normals"] = page_file_name(names.normals, p, l.pages);
      page["first_frame"] = l.page_first_frame(p);
      page["frame_count"] = l.page_frames(p);
      page["height"] = l.page_height(p);
      table.push_back(std::move(page));
    }
    doc["frames_per_page"] = l.frames_per_page;
    doc["page_table"] = std::move(table);
  }
  doc["width"] = l.width;
  doc["height"] = l.height;
  doc["used_width"] = l.used_width;
  doc["used_height"] = l.used_height;
  doc["texel"] = texel_formula(l);
  doc["decode"] = {{"position", position_formula(e)}, {"normal", normal_formula(e)},
                   {"between_frames", "linear interpolation of the decoded neighbours"}};
  doc["remap"] = e.remapped ? box_json(e.bounds) : Json(nullptr);
  doc["axes"] = axes(l.format.profile);
  doc["bounds"] = box_json(info.clip_bounds);
  Json frames = Json::array();
  for (const Box& b : info.frame_bounds) frames.push_back(box_json(b));
  doc["frame_bounds"] = std::move(frames);
  doc["vertex_order"] =
      "the sources' vertices in order, each source one primitive's vertices in accessor order; primitives that "
      "share a source's vertex accessors (its shared_by) add none; the rest mesh's TEXCOORD_1 holds each vertex's lookup";
  Json sources = Json::array();
  size_t first = 0;
  for (const VatSource& s : info.sources) {
    sources.push_back({{"node", s.node}, {"node_name", s.node_name}, {"mesh", s.mesh}, {"mesh_name", s.mesh_name},
                       {"primitive", s.primitive}, {"shared_by", s.shared_by}, {"first_vertex", first},
                       {"vertex_count", s.vertices}});
    first += s.vertices;
  }
  doc["sources"] = std::move(sources);
  Json files = {{"positions", names.positions}};
  if (!names.normals.empty()) files["normals"] = names.normals;
  files["rest_mesh"] = names.rest_mesh;
  files["lookup"] = l.format.profile == VatProfile::kDqskin ? "TEXCOORD_1 = integer texel (x, y) of frame 0"
                                                            : "TEXCOORD_1 = texel centre of frame 0 in [0, 1]";
  if (!names.profile_side_file.empty()) files["profile_side_file"] = names.profile_side_file;
  doc["files"] = std::move(files);
  // Version 1's description of the images, kept for its readers.
  const bool raw = l.format.profile == VatProfile::kDqskin && !is_png(l.format.type);
  Json attributes = {{"positions", {{"file", names.positions},
                                    {"channels", l.position_channels() == 4 ? "RGBA" : "RGB"},
                                    {"type", type_name(l.format.type)},
                                    {"content", raw ? "world-space position xyz, w = 1" : position_formula(e)}}}};
  if (!names.normals.empty()) {
    const TexelType nt = *e.normal_image_type();
    attributes["normals"] = {{"file", names.normals},
                             {"channels", normal_channels(e) == 4 ? "RGBA" : "RGB"},
                             {"type", type_name(nt)},
                             {"content", raw ? "unit normal xyz (0 where the primitive has none), w = 0" : normal_formula(e)}};
  }
  doc["attributes"] = std::move(attributes);
  if (info.plan)
    doc["plan"] = {{"encoding", info.plan->type},
                   {"frame_step", info.plan->step},
                   {"expected_error", info.plan->expected_error},
                   {"encoding_error", info.plan->encoding_error},
                   {"interpolation_error", info.plan->interpolation_error},
                   {"gpu_bytes", info.plan->bytes}};
  if (check) doc["decode_check"] = check->to_json();
  return dump(doc, 2);
}

std::string profile_side_file(const VatEncoding& e, const VatClipInfo& info) {
  const VatLayout& l = e.layout;
  switch (l.format.profile) {
    case VatProfile::kDqskin: return {};
    case VatProfile::kOpenVat: {
      Json doc;
      doc["os-remap"] = {{"Min", vec(e.bounds.lo)}, {"Max", vec(e.bounds.hi)}, {"Frames", l.frames}};
      // OpenVAT's animation list: frames counted from 1 over the whole texture.
      Json animations = Json::object();
      for (const VatClipEntry& c : clip_table(info, l))
        animations[c.name] = {{"startFrame", c.first_frame + 1}, {"endFrame", c.first_frame + c.frame_count},
                              {"framerate", c.fps > 0 ? c.fps : 0.0}, {"looping", c.loops}};
      doc["animations"] = std::move(animations);
      return dump(doc, 4);
    }
    case VatProfile::kHoudini: {
      const Box b = houdini_encoded_bounds(info.clip_bounds, l, info.asset);
      // json.dump(sort_keys=True, indent=4): the keys in this order are already sorted.
      Json entry = {{"Axis System", "Right-Handed Y-Up"},
                    {"Bound Max X", b.hi.x}, {"Bound Max Y", b.hi.y}, {"Bound Max Z", b.hi.z},
                    {"Bound Min X", b.lo.x}, {"Bound Min Y", b.lo.y}, {"Bound Min Z", b.lo.z},
                    {"Frame Count", l.frames},
                    {"Houdini FPS", info.fps > 0 ? info.fps : 0.0},
                    {"Name", info.asset},
                    {"Two Position Textures", 0}};
      return dump(Json::array({std::move(entry)}), 4);
    }
  }
  return {};
}

}  // namespace dqskin::texture
