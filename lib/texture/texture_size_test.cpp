// Every VAT and bone-texture profile within --max-size (vat_format.hpp, bone_profiles.hpp): layouts that
// can wrap do, and one that cannot fit is refused with the size it needs and the smallest --max-size that
// would fit it, which the tests check by planning at that size and one texel below.
#include "vat_format.hpp"
#include "bone_profiles.hpp"

#include "dqskin/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace dqskin::texture {
namespace {

const VatFormat kDqskin{VatProfile::kDqskin, TexelType::kFloat32, NormalMode::kSeparate};
const VatFormat kOpenVat{VatProfile::kOpenVat, TexelType::kHalf, NormalMode::kPacked};
const VatFormat kHoudini{VatProfile::kHoudini, TexelType::kFloat32, NormalMode::kSeparate};

// The refusal's text, or "" when the layout fits.
std::string refusal(const VatFormat& f, size_t vertices, size_t frames, size_t max_size) {
  try {
    plan_vat_layout(f, vertices, frames, max_size, false, "clip 0");
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

// The N of "--max-size N would fit" in `message` (its last --max-size), or 0.
size_t suggested(const std::string& message) {
  const size_t at = message.rfind("--max-size ");
  return at == std::string::npos ? 0 : std::stoul(message.substr(at + 11));
}

TEST(TextureSize, EveryProfileWrapsAWideMeshWithin8192) {
  // BrainStem's 34,159 vertices, which OpenVAT's single row put in an image 34,159 texels wide.
  for (const VatFormat& f : {kDqskin, kOpenVat, kHoudini}) {
    SCOPED_TRACE(to_string(f.profile));
    const VatLayout l = plan_vat_layout(f, 34159, 100, 8192, false, "t");
    EXPECT_LE(l.width, 8192u);
    EXPECT_LE(l.height, 8192u);
    EXPECT_GT(l.wraps, 1u);
    // Every vertex of every frame has a texel of its own inside the image.
    for (size_t v : {size_t(0), size_t(8191), size_t(8192), size_t(34158)})
      for (size_t f2 : {size_t(0), size_t(99)}) {
        const TexelAt at = l.packed_normal(v, f2);
        EXPECT_LT(at.x, l.width);
        EXPECT_LT(at.y, l.page_height(at.page));
      }
  }
}

TEST(TextureSize, RefusalNamesTheSmallestMaxSizeThatFits) {
  EXPECT_EQ(refusal(kHoudini, 34159, 1047, 4096),
            "clip 0: 34159 vertices × 1047 frames do not fit an image 4096 texels high (at most 455 frames do); "
            "lower --fps, or use the dqskin profile, which splits frames over pages; it needs 6282 × 6282 texels: "
            "--max-size 6282 would fit");
  struct Case {
    VatFormat format;
    size_t vertices, frames, max_size;
  };
  for (const Case& c : {Case{kHoudini, 9000, 9001, 8192}, Case{kOpenVat, 9000, 9001, 8192},
                        Case{kOpenVat, 34159, 3000, 8192}, Case{kDqskin, 100000, 2, 256}}) {
    SCOPED_TRACE(std::string(to_string(c.format.profile)) + " " + std::to_string(c.vertices));
    const std::string message = refusal(c.format, c.vertices, c.frames, c.max_size);
    const size_t n = suggested(message);
    ASSERT_GT(n, c.max_size) << message;
    EXPECT_EQ(refusal(c.format, c.vertices, c.frames, n), "") << "the suggested size fits";
    EXPECT_NE(refusal(c.format, c.vertices, c.frames, n - 1), "") << "and is the smallest that does";
    const VatLayout l = plan_vat_layout(c.format, c.vertices, c.frames, n, false, "t");
    EXPECT_NE(message.find("it needs " + std::to_string(l.width) + " × " + std::to_string(l.height) + " texels"),
              std::string::npos)
        << message;
  }
}

TEST(TextureSize, BoneTexturesWithinMaxSizeOrRefusedWithTheSizeThatFits) {
  EXPECT_EQ(bone_size_problem(BoneProfile::kMat4, bone_image_size(BoneProfile::kMat4, 60, 8192), 8192), "");
  EXPECT_EQ(bone_size_problem(BoneProfile::kMat4, bone_image_size(BoneProfile::kMat4, 2, 9001), 8192),
            "the mat4 bone texture needs 12 × 9001 texels, over --max-size 8192 (its runtime reads one row per "
            "frame and does not wrap); --max-size 9001 would fit, as would fewer frames (--fps)");
  // 2,048 joints of Babylon.js's 4 texels, and its identity: 8,196 texels a row.
  EXPECT_EQ(suggested(bone_size_problem(BoneProfile::kMat4, bone_image_size(BoneProfile::kMat4, 2048, 10), 8192)),
            8196u);
  EXPECT_EQ(suggested(bone_size_problem(BoneProfile::kDq, bone_image_size(BoneProfile::kDq, 5000, 10, 2), 8192)),
            10000u);
  const BoneImageSize cocos = bone_image_size(BoneProfile::kDqCocos, 2, 9001);
  EXPECT_EQ(cocos.width, cocos.height);
  EXPECT_EQ(cocos.width % 12, 0u);
  EXPECT_GE(cocos.width * cocos.height, 3u * 2 * 9001);
  EXPECT_EQ(suggested(bone_size_problem(BoneProfile::kDqCocos, cocos, 200)), cocos.width);
  EXPECT_EQ(bone_size_problem(BoneProfile::kDqCocos, cocos, 0), "") << "0: no bound";
}

}  // namespace
}  // namespace dqskin::texture
