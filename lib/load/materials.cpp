#include "materials.hpp"

#include <cmath>
#include <string>
#include <vector>
#include <limits>

namespace dqskin::gltf {
namespace {

// Appearance does not change the deformation, so a broken reference or value here is not worth refusing a
// file that bakes: it is dropped (or its default used) with a warning, and the renderer draws without it.
// Geometry and animation errors stay fatal (load.cpp, mesh.cpp).
struct Problem {
  std::string message;
};
[[noreturn]] void drop(const std::string& message) { throw Problem{message}; }

std::string at(const char* kind, size_t index) { return std::string(kind) + " " + std::to_string(index); }

TextureRef read_texture_ref(const tinygltf::TextureInfo& info, size_t textures, const std::string& what) {
  TextureRef ref;
  if (info.index < 0) return ref;
  if (size_t(info.index) >= textures) drop(what + ": texture " + std::to_string(info.index) + " does not exist");
  ref.texture = info.index;
  ref.texcoord = info.texCoord;
  return ref;
}

// A number that stays finite as a float: JSON holds no infinity, but 1e39 is one as a float.
bool finite_float(const tinygltf::Value& v) {
  return v.IsNumber() && std::abs(v.GetNumberAsDouble()) <= double(std::numeric_limits<float>::max());
}

glm::vec2 read_vec2(const tinygltf::Value& ext, const char* name, glm::vec2 fallback, const std::string& what) {
  if (!ext.Has(name)) return fallback;
  const tinygltf::Value& v = ext.Get(name);
  // tinygltf leaves out null elements (and an empty array), so [null, 1] arrives as one number.
  if (!v.IsArray() || v.ArrayLen() != 2 || !finite_float(v.Get(0)) || !finite_float(v.Get(1)))
    drop(what + ": KHR_texture_transform " + name + " must be 2 finite numbers");
  return {float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble())};
}

// KHR_texture_transform of `info`, into `ref` (left as it is when a value is bad). Its texCoord was
// checked on the JSON (schema_values.cpp: a bad one is removed with the whole transform and a warning).
void read_texture_transform(const tinygltf::TextureInfo& info, const std::string& what, TextureRef& ref) {
  const auto found = info.extensions.find("KHR_texture_transform");
  if (found == info.extensions.end()) return;
  // tinygltf keeps an extension only when it is a JSON object, and an empty object arrives as null.
  const tinygltf::Value& ext = found->second;
  if (!ext.IsObject()) return;
  TextureTransform t;
  t.offset = read_vec2(ext, "offset", t.offset, what);
  t.scale = read_vec2(ext, "scale", t.scale, what);
  if (ext.Has("rotation")) {
    if (!finite_float(ext.Get("rotation"))) drop(what + ": KHR_texture_transform rotation must be a finite number");
    t.rotation = float(ext.Get("rotation").GetNumberAsDouble());
  }
  int texcoord = ref.texcoord;
  if (ext.Has("texCoord")) {
    const tinygltf::Value& v = ext.Get("texCoord");
    if (!v.IsInt() || v.GetNumberAsInt() < 0) drop(what + ": KHR_texture_transform texCoord must be an index");
    texcoord = v.GetNumberAsInt();
  }
  ref.transform = t;
  ref.texcoord = texcoord;
}

// Runs `read`; a Problem becomes a warning ending in `consequence`, and is returned (empty when none).
template <typename Read>
std::string or_warn(Asset& asset, const char* consequence, Read read) {
  try {
    read();
    return {};
  } catch (const Problem& p) {
    asset.warnings.push_back(p.message + "; " + consequence);
    return asset.warnings.back();
  }
}

void read_materials(const tinygltf::Model& m, Asset& asset) {
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const tinygltf::Material& mat = m.materials[i];
    const std::string what = at("material", i);
    Material out;
    out.name = mat.name;
    or_warn(asset, "white is used", [&] {
      const std::vector<double>& factor = mat.pbrMetallicRoughness.baseColorFactor;
      // §5.22.2: four components, each in [0, 1]
      if (factor.size() != 4) drop(what + ": baseColorFactor must have 4 numbers");
      for (double x : factor)
        if (!(x >= 0 && x <= 1)) drop(what + ": baseColorFactor must be 4 numbers in [0, 1]");
      for (int c = 0; c < 4; ++c) out.base_color[c] = float(factor[size_t(c)]);
    });
    or_warn(asset, "it is drawn without the texture", [&] {
      out.base_color_texture =
          read_texture_ref(mat.pbrMetallicRoughness.baseColorTexture, m.textures.size(), what + " baseColorTexture");
    });
    if (out.base_color_texture.texture >= 0)
      or_warn(asset, "the transform is ignored", [&] {
        read_texture_transform(mat.pbrMetallicRoughness.baseColorTexture, what + " baseColorTexture",
                               out.base_color_texture);
      });
    if (out.base_color_texture.texcoord > 1)
      asset.warnings.push_back(what + ": its base color texture reads TEXCOORD_" +
                               std::to_string(out.base_color_texture.texcoord) +
                               ", but dqskin reads TEXCOORD_0 and _1 only; it is drawn without the texture");
    // §5.19: alphaMode is OPAQUE, MASK or BLEND; alphaCutoff is at least 0.
    or_warn(asset, "it is drawn opaque", [&] {
      if (mat.alphaMode == "MASK") out.alpha_mode = AlphaMode::kMask;
      else if (mat.alphaMode == "BLEND") out.alpha_mode = AlphaMode::kBlend;
      else if (mat.alphaMode != "OPAQUE") drop(what + ": alphaMode '" + mat.alphaMode + "' is not OPAQUE, MASK or BLEND");
    });
    or_warn(asset, "0.5 is used", [&] {
      if (!(mat.alphaCutoff >= 0) || !std::isfinite(mat.alphaCutoff)) drop(what + ": alphaCutoff must be at least 0");
      out.alpha_cutoff = float(mat.alphaCutoff);
    });
    asset.materials.push_back(std::move(out));
  }
  for (size_t i = 0; i < asset.meshes.size(); ++i)
    for (size_t j = 0; j < asset.meshes[i].primitives.size(); ++j) {
      int& material = asset.meshes[i].primitives[j].material;
      if (material >= int(asset.materials.size())) {
        asset.warnings.push_back(at("mesh", i) + " primitive " + std::to_string(j) + ": material " + std::to_string(material) +
                                 " does not exist; the default material is used");
        material = -1;
      }
    }
}

// §5.26's enum values were checked on the JSON (schema_values.cpp: a bad one is removed with a warning,
// so tinygltf's default stands here); filters may be left undefined (tinygltf: -1).
Sampler read_sampler(const tinygltf::Sampler& s) {
  Sampler out;
  out.mag_filter = s.magFilter == -1 ? 0 : s.magFilter;
  out.min_filter = s.minFilter == -1 ? 0 : s.minFilter;
  out.wrap_s = s.wrapS;
  out.wrap_t = s.wrapT;
  return out;
}

// The image an extension puts in a texture (EXT_texture_webp, KHR_texture_basisu: `source` inside the
// extension object), or -1 when the texture has no such extension. Throws Problem for an index that is not
// an image (schema_values.cpp removed one that is not an index at all).
int extension_image(const tinygltf::Texture& t, const char* name, size_t images, const std::string& what) {
  const auto found = t.extensions.find(name);
  if (found == t.extensions.end() || !found->second.IsObject() || !found->second.Has("source")) return -1;
  const tinygltf::Value& source = found->second.Get("source");
  if (!source.IsInt() || source.GetNumberAsInt() < 0) return -1;
  if (size_t(source.GetNumberAsInt()) >= images)
    drop(what + ": " + name + " source " + std::to_string(source.GetNumberAsInt()) + " does not exist");
  return source.GetNumberAsInt();
}

// Which image a texture draws. EXT_texture_webp's image first: OpenImageIO decodes WebP, and the core
// `source` is only the fallback for viewers without the extension. KHR_texture_basisu's KTX2 image is not
// decoded (that needs a Basis Universal transcoder), so its core `source`, the PNG or JPEG fallback, is
// drawn; without one the texture is left out and its materials are drawn with their factors, which one
// warning for the whole file says (`basisu_only` collects the textures).
void read_textures(const tinygltf::Model& m, Asset& asset) {
  std::vector<size_t> basisu_only;
  for (size_t i = 0; i < m.textures.size(); ++i) {
    const tinygltf::Texture& t = m.textures[i];
    const std::string what = at("texture", i);
    Texture out;
    int webp = -1;
    or_warn(asset, "its core source is used",
            [&] { webp = extension_image(t, "EXT_texture_webp", m.images.size(), what); });
    int basisu = -1;
    or_warn(asset, "it is ignored", [&] { basisu = extension_image(t, "KHR_texture_basisu", m.images.size(), what); });
    or_warn(asset, "textures using it are not drawn", [&] {
      if (t.source >= 0 && size_t(t.source) >= m.images.size()) drop(what + ": image " + std::to_string(t.source) + " does not exist");
      if (webp >= 0) {
        out.image = webp;
        return;
      }
      if (t.source < 0 && basisu >= 0) {
        basisu_only.push_back(i);
        return;
      }
      // An extension dqskin knows no image of may leave out the core source (a PNG or JPEG fallback).
      if (t.source < 0)
        drop(what + (t.extensions.empty() ? ": has no image"
                                          : ": has no PNG or JPEG source (only an extension's image, which dqskin does not read)"));
      out.image = t.source;
    });
    or_warn(asset, "the default sampler is used", [&] {
      if (t.sampler >= 0 && size_t(t.sampler) >= m.samplers.size())
        drop(what + ": sampler " + std::to_string(t.sampler) + " does not exist");
      if (t.sampler >= 0) out.sampler = read_sampler(m.samplers[size_t(t.sampler)]);
    });
    asset.textures.push_back(out);
  }
  if (!basisu_only.empty()) {
    std::string list;
    for (size_t i : basisu_only) list += (list.empty() ? "" : ", ") + std::to_string(i);
    asset.warnings.push_back((basisu_only.size() == 1 ? "texture " + list + " has" : "textures " + list + " have") +
                             " only a KTX2 image (KHR_texture_basisu), which dqskin does not decode, and no PNG or JPEG "
                             "fallback; materials using " + (basisu_only.size() == 1 ? "it" : "them") +
                             " are drawn with their factors");
  }
  for (const tinygltf::Image& image : m.images) {
    EncodedImage out;
    out.name = image.name;
    out.mime_type = image.mimeType;
    // A data URI is embedded; keep only a file's URI for messages.
    if (image.bufferView < 0 && image.uri.rfind("data:", 0) != 0) out.uri = image.uri;
    if (image.as_is) out.bytes.assign(image.image.begin(), image.image.end());  // set by the loader's image callback
    asset.images.push_back(std::move(out));
  }
}

// §5.12-5.14: perspective yfov and znear above 0, zfar above znear when given, aspectRatio above 0 when
// given; orthographic xmag and ymag not 0, znear at least 0, zfar above znear.
void read_camera(const tinygltf::Camera& c, const std::string& what, SceneCamera& out) {
  auto finite = [&](std::initializer_list<double> values) {
    for (double v : values)
      if (!std::isfinite(v)) drop(what + ": has a number that is not finite");
  };
  if (c.type == "perspective") {
    const tinygltf::PerspectiveCamera& p = c.perspective;
    finite({p.yfov, p.znear, p.zfar, p.aspectRatio});
    if (!(p.yfov > 0)) drop(what + ": yfov must be above 0");
    if (!(p.znear > 0)) drop(what + ": znear must be above 0");
    if (p.zfar != 0 && !(p.zfar > p.znear)) drop(what + ": zfar must be above znear");
    if (p.aspectRatio < 0) drop(what + ": aspectRatio must be above 0");
    out.yfov = p.yfov;
    out.aspect_ratio = p.aspectRatio;
    out.znear = p.znear;
    out.zfar = p.zfar;
  } else if (c.type == "orthographic") {
    const tinygltf::OrthographicCamera& o = c.orthographic;
    finite({o.xmag, o.ymag, o.znear, o.zfar});
    out.orthographic = true;
    if (o.xmag == 0 || o.ymag == 0) drop(what + ": xmag and ymag must not be 0");
    if (!(o.znear >= 0)) drop(what + ": znear must be at least 0");
    if (!(o.zfar > o.znear)) drop(what + ": zfar must be above znear");
    out.xmag = o.xmag;
    out.ymag = o.ymag;
    out.znear = o.znear;
    out.zfar = o.zfar;
  } else {
    drop(what + ": type '" + c.type + "' is not perspective or orthographic");
  }
}

void read_cameras(const tinygltf::Model& m, Asset& asset) {
  for (size_t i = 0; i < m.cameras.size(); ++i) {
    const tinygltf::Camera& c = m.cameras[i];
    const std::string what = at("camera", i);
    SceneCamera out;
    out.name = c.name;
    out.problem = or_warn(asset, "it cannot be rendered through", [&] { read_camera(c, what, out); });
    asset.cameras.push_back(std::move(out));
  }
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const int camera = m.nodes[i].camera;
    if (camera >= 0 && size_t(camera) >= asset.cameras.size()) {
      asset.warnings.push_back(at("node", i) + ": camera " + std::to_string(camera) + " does not exist; it is ignored");
      continue;
    }
    asset.nodes[i].camera = camera < 0 ? -1 : camera;
  }
}


}  // namespace

void read_appearance(const tinygltf::Model& model, Asset& asset) {
  read_materials(model, asset);
  read_textures(model, asset);
  read_cameras(model, asset);
}

}  // namespace dqskin::gltf

namespace dqskin {

glm::mat3 TextureTransform::matrix() const {
  const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
  const double sx = double(scale.x), sy = double(scale.y);
  return glm::mat3(float(c * sx), float(-s * sx), 0.0f,  // column 0
                   float(s * sy), float(c * sy), 0.0f,   // column 1
                   offset.x, offset.y, 1.0f);            // column 2
}

}  // namespace dqskin
