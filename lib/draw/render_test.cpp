// Rendering: equal inputs give equal images, EGL and OSMesa agree, the automatic camera frames the model,
// normals shading shows known normals, PNGs are sRGB-encoded. Tests that need a backend the machine lacks
// skip with the reason.
#include "dqskin/camera.hpp"
#include "dqskin/image_output.hpp"
#include "dqskin/renderer.hpp"

#include "dqskin/error.hpp"
#include "dqskin/deformer.hpp"
#include "dqskin/load.hpp"
#include "../test_support/gpu_context.hpp"

#include <OpenImageIO/imageio.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

using testing_support::context_or_null;

// Every frame of `clip` at `times`, deformed on the GPU (mode dqs), as one batch per deformer batch.
std::vector<DeformedBatch> deform(GpuContext& context, const Asset& asset, const std::vector<MeshInstance>& instances,
                                  const Clip* clip, const std::vector<double>& times) {
  DeformerOptions options;
  options.backend = testing_support::backend_of(context);
  const std::unique_ptr<Deformer> deformer = make_deformer(&context, asset, instances, options);
  std::vector<DeformedBatch> out;
  deformer->run(clip, times, [&](const DeformedBatch& b) { out.push_back(b); });
  return out;
}

// The rig's frame at `time` rendered with the automatic camera framed on that frame alone.
Image render_rig(GpuContext& context, const std::string& path, double time, const RendererOptions& options = {}) {
  const Asset asset = load_asset(path);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const std::vector<DeformedBatch> batches =
      deform(context, asset, instances, asset.clips.empty() ? nullptr : &asset.clips[0], {time});
  const FrameView frame = frame_view(batches.at(0), 0);
  Bounds box;
  box.add(frame);
  Renderer renderer(context, asset, instances, options);
  return renderer.render(frame, frame_camera(box, {}, double(options.width) / double(options.height)));
}

const std::string kArm = std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf";

bool is_background(const Image& image, size_t pixel, const glm::vec4& background) {
  for (size_t c = 0; c < 3; ++c)
    if (std::abs(image.rgba[pixel * 4 + c] - background[int(c)]) > 1e-3f) return false;
  return true;
}

TEST(Render, TwoRendersOfARigAreByteIdentical) {
  const auto context = context_or_null(Backend::kAuto);
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  const Image a = render_rig(*context, kArm, 0.5);
  const Image b = render_rig(*context, kArm, 0.5);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(0, std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)));
}

// Both backends are Mesa's llvmpipe here; another driver may round differently. Threshold: every channel
// within 2/255 of the other backend's, and at most 0.5 % of the pixels differ at all.
TEST(Render, EglAndOsMesaAgree) {
  const auto egl = context_or_null(Backend::kEgl);
  if (!egl) GTEST_SKIP() << "no EGL context";
  const Image a = render_rig(*egl, kArm, 0.5);
  const auto osmesa = context_or_null(Backend::kOsMesa);
  if (!osmesa) GTEST_SKIP() << "no OSMesa context";
  const Image b = render_rig(*osmesa, kArm, 0.5);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  float worst = 0;
  size_t differing = 0;
  for (size_t p = 0; p < a.rgba.size() / 4; ++p) {
    float d = 0;
    for (size_t c = 0; c < 4; ++c) d = std::max(d, std::abs(a.rgba[p * 4 + c] - b.rgba[p * 4 + c]));
    worst = std::max(worst, d);
    differing += d > 0 ? 1 : 0;
  }
  const bool identical = std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
  std::printf("EGL vs OSMesa: %s; largest channel difference %g, %zu pixels differ\n",
              identical ? "byte-identical" : "different", double(worst), differing);
  EXPECT_LE(worst, 2.0f / 255.0f);
  EXPECT_LE(double(differing), 0.005 * double(a.rgba.size() / 4));
}

TEST(Render, AutomaticCameraCentersAndFillsTheView) {
  const auto context = context_or_null(Backend::kAuto);
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  RendererOptions options;
  options.width = 320;
  options.height = 240;
  for (double time : {0.0, 1.0}) {
    const Image image = render_rig(*context, kArm, time, options);
    int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
    size_t covered = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        if (!is_background(image, size_t(y) * size_t(image.width) + size_t(x), options.background)) {
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
          ++covered;
        }
    ASSERT_GE(x1, 0) << "nothing drawn at t = " << time;
    // The box's corners fit with a margin, so the model stays inside and touches neither edge ...
    EXPECT_GT(x0, 0);
    EXPECT_GT(y0, 0);
    EXPECT_LT(x1, image.width - 1);
    EXPECT_LT(y1, image.height - 1);
    // ... and fills most of the view in one direction at least.
    EXPECT_GT(std::max(double(x1 - x0) / image.width, double(y1 - y0) / image.height), 0.6) << "t = " << time;
    EXPECT_GT(double(covered) / (image.width * image.height), 0.05) << "t = " << time;
    // Centered: the drawn pixels' box is centered within a tenth of the image.
    EXPECT_NEAR(0.5 * (x0 + x1), 0.5 * image.width, 0.1 * image.width) << "t = " << time;
    EXPECT_NEAR(0.5 * (y0 + y1), 0.5 * image.height, 0.1 * image.height) << "t = " << time;
  }
}

// A unit square in the plane z = 0 facing +Z, drawn by one node without a skin.
Asset square_asset() {
  Asset asset;
  Primitive p;
  p.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  p.normals.assign(4, glm::vec3(0, 0, 1));
  p.indices = {0, 1, 2, 0, 2, 3};
  asset.meshes.push_back({"square", {p}, {}});
  Node node;
  node.mesh = 0;
  asset.nodes.push_back(node);
  asset.scenes.push_back({"", {0}});
  asset.default_scene = 0;
  return asset;
}

TEST(Render, NormalsShadingShowsTheNormalAsAColor) {
  const auto context = context_or_null(Backend::kAuto);
  if (!context) GTEST_SKIP() << "no OpenGL 4.3 context";
  const Asset asset = square_asset();
  const std::vector<MeshInstance> instances = mesh_instances(asset, 0);
  // The square turned so that its normal is n, seen from straight ahead of that normal.
  struct Case {
    glm::vec3 normal;
    double yaw, pitch;
  };
  for (const Case& c : {Case{{0, 0, 1}, 0, 0}, Case{{1, 0, 0}, 90, 0}, Case{{0, 1, 0}, 0, 89}}) {
    std::vector<float> positions, normals;
    // An orthonormal basis (u, v, n) carries the square's (x, y) into the plane of normal n.
    const glm::vec3 u = std::abs(c.normal.z) > 0.5f ? glm::vec3(1, 0, 0) : glm::normalize(glm::cross(glm::vec3(0, 0, 1), c.normal));
    const glm::vec3 v = glm::cross(c.normal, u);
    for (const glm::vec3& p : asset.meshes[0].primitives[0].positions) {
      const glm::vec3 q = p.x * u + p.y * v;
      positions.insert(positions.end(), {q.x, q.y, q.z});
      normals.insert(normals.end(), {c.normal.x, c.normal.y, c.normal.z});
    }
    FrameView frame;
    frame.primitives.push_back({4, positions, normals, {}});
    Bounds box;
    box.add(frame);
    RendererOptions options;
    options.width = options.height = 64;
    options.shade = Shade::kNormals;
    Renderer renderer(*context, asset, instances, options);
    CameraOptions camera;
    camera.yaw = c.yaw;
    camera.pitch = c.pitch;
    const Image image = renderer.render(frame, frame_camera(box, camera, 1.0));
    const size_t center = (32 * 64 + 32) * 4;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(image.rgba[center + size_t(k)], 0.5f * c.normal[k] + 0.5f, 2e-3f) << "normal " << c.normal[k] << " channel " << k;
  }
}

TEST(Render, WeightsShadingNeedsAKnownJoint) {
  const Asset asset = load_asset(kArm);
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  EXPECT_THROW(joint_weights(asset, instances, "no such joint"), std::runtime_error);
  // Every vertex's weights over the skin's joints sum to 1.
  const Skin& skin = asset.skins.at(0);
  std::vector<std::vector<float>> sum;
  for (int joint : skin.joints) {
    const auto w = joint_weights(asset, instances, asset.nodes[size_t(joint)].name);
    if (sum.empty()) sum.assign(w.size(), {});
    for (size_t p = 0; p < w.size(); ++p) {
      sum[p].resize(w[p].size(), 0.0f);
      for (size_t i = 0; i < w[p].size(); ++i) sum[p][i] += w[p][i];
    }
  }
  for (const auto& prim : sum)
    for (float s : prim) EXPECT_NEAR(s, 1.0f, 1e-6f);
}

TEST(RenderOutput, PngIsEightBitSrgbAndExrIsLinearFloat) {
  const fs::path dir = fs::temp_directory_path() / ("dqskin_render_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Image image;
  image.width = 2;
  image.height = 1;
  image.rgba = {0.5f, 0.0f, 1.0f, 1.0f, 0.0031308f, 0.2f, 2.0f, 0.5f};
  write_image((dir / "a.png").string(), image, ImageFormat::kPng);
  write_image((dir / "a.exr").string(), image, ImageFormat::kExr);
  auto read = [](const fs::path& path, OIIO::TypeDesc type, void* pixels) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // the bytes as stored, not multiplied by alpha
    auto in = OIIO::ImageInput::open(path.string(), &config);
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().nchannels, 4);
    EXPECT_EQ(in->spec().format, type);
    ASSERT_TRUE(in->read_image(0, 0, 0, 4, type, pixels));
  };
  uint8_t png[8] = {};
  read(dir / "a.png", OIIO::TypeDesc::UINT8, png);
  // sRGB(0.5) = 0.7354 → 188; sRGB(0.0031308) = 0.04045 → 10; sRGB(0.2) = 0.4845 → 124; alpha stays linear.
  const uint8_t expected[8] = {188, 0, 255, 255, 10, 124, 255, 128};
  for (size_t i = 0; i < 8; ++i) EXPECT_EQ(png[i], expected[i]) << "byte " << i;
  float exr[8] = {};
  read(dir / "a.exr", OIIO::TypeDesc::FLOAT, exr);
  for (size_t i = 0; i < 8; ++i) EXPECT_EQ(exr[i], image.rgba[i]) << "value " << i;
  fs::remove_all(dir);
}


// A frame of one flat color, for the sheet and GIF tests (no GPU needed).
Image flat_frame(int width, int height, float gray) {
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(size_t(width) * size_t(height) * 4, gray);
  for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 1.0f;
  return image;
}

std::vector<char> file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Five 64x48 frames in 32-pixel cells: 3 columns (ceil(sqrt(5))), 2 rows of 32x24 cells with gaps.
TEST(RenderOutput, ContactSheetIsANearSquareGridWithFrameNumbers) {
  const fs::path dir = fs::temp_directory_path() / ("dqskin_sheet_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ContactSheet sheet(32);
  for (int i = 0; i < 5; ++i) sheet.add(flat_frame(64, 48, 0.5f), 10 + i);
  const Image8 image = sheet.compose();
  EXPECT_EQ(image.width, 3 * 32 + 4 * kSheetGap);
  EXPECT_EQ(image.height, 2 * 24 + 3 * kSheetGap);
  auto pixel = [&](int x, int y) { return image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4]; };
  const uint8_t gray = to_srgb8(flat_frame(1, 1, 0.5f)).rgba[0];
  // Away from the label the cell is the frame; in the label (top left) the digit "1" of "10" is white
  // (its glyph's top row sets column 2) on a black box.
  EXPECT_EQ(pixel(kSheetGap + 20, kSheetGap + 20), gray);
  EXPECT_EQ(pixel(kSheetGap + 1 + 2, kSheetGap + 1), 255);
  EXPECT_EQ(pixel(kSheetGap, kSheetGap), 0);
  int label_differs = 0;
  for (int y = kSheetGap; y < kSheetGap + 9; ++y)
    for (int x = kSheetGap; x < kSheetGap + 13; ++x) label_differs += pixel(x, y) != gray;
  EXPECT_GT(label_differs, 13 * 9 / 2);
  // The sixth cell is empty: the gap color.
  EXPECT_NE(pixel(image.width - kSheetGap - 10, image.height - kSheetGap - 10), gray);

  sheet.write((dir / "a.png").string());
  sheet.write((dir / "b.png").string());
  auto in = OIIO::ImageInput::open((dir / "a.png").string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().width, image.width);
  EXPECT_EQ(in->spec().height, image.height);
  in.reset();
  EXPECT_EQ(file_bytes(dir / "a.png"), file_bytes(dir / "b.png"));
  fs::remove_all(dir);
}

TEST(RenderOutput, GifHasOneSubimagePerFrame) {
  const fs::path dir = fs::temp_directory_path() / ("dqskin_gif_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* name : {"a.gif", "b.gif"}) {
    GifWriter gif((dir / name).string(), 25);
    for (int i = 0; i < 3; ++i) gif.add(flat_frame(40, 30, 0.25f * float(i)));
    EXPECT_EQ(gif.frames(), 3u);
    gif.commit();
  }
  EXPECT_EQ(file_bytes(dir / "a.gif"), file_bytes(dir / "b.gif"));
  auto in = OIIO::ImageInput::open((dir / "a.gif").string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().width, 40);
  EXPECT_EQ(in->spec().height, 30);
  int subimages = 0;
  while (in->seek_subimage(subimages, 0)) ++subimages;
  EXPECT_EQ(subimages, 3);
  in.reset();
  // 25 frames per second: every Graphic Control Extension (21 F9 04) delays 4 hundredths of a second.
  const std::vector<char> bytes = file_bytes(dir / "a.gif");
  int delays = 0;
  for (size_t i = 0; i + 5 < bytes.size(); ++i)
    if (bytes[i] == '\x21' && bytes[i + 1] == '\xF9' && bytes[i + 2] == '\x04') {
      EXPECT_EQ(bytes[i + 4], 4);
      EXPECT_EQ(bytes[i + 5], 0);
      ++delays;
    }
  EXPECT_EQ(delays, 3);
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------------
// glTF cameras (§3.10): where a world point lands in normalized device coordinates.

glm::dvec3 ndc(const Camera& camera, const glm::dvec3& world) {
  const glm::dvec4 clip = glm::dmat4(camera.projection) * glm::dmat4(camera.view) * glm::dvec4(world, 1.0);
  return glm::dvec3(clip) / clip.w;
}

TEST(SceneCamera, PerspectiveLooksDownLocalMinusZInTheImagesAspectRatio) {
  SceneCamera perspective;
  perspective.yfov = 0.8;
  perspective.aspect_ratio = 3.0;  // sets the default image size; the projection uses the image's ratio
  perspective.znear = 0.5;
  perspective.zfar = 100;
  Mat4<double> world(1.0);
  world[3] = {1, 2, 5, 1};  // at (1, 2, 5), looking towards −z
  const Camera camera = scene_camera(perspective, world, 2.0);
  const double half_height = 5 * std::tan(0.4);
  EXPECT_NEAR(ndc(camera, {1, 2, 0}).x, 0, 1e-6);
  EXPECT_NEAR(ndc(camera, {1, 2, 0}).y, 0, 1e-6);
  EXPECT_NEAR(ndc(camera, {1, 2 + half_height, 0}).y, 1, 1e-5);
  EXPECT_NEAR(ndc(camera, {1 + 2 * half_height, 2, 0}).x, 1, 1e-5) << "not stretched to the camera's 3:1";
  EXPECT_NEAR(ndc(camera, {1, 2, 4.5}).z, -1, 1e-5) << "znear maps to −1";
  EXPECT_EQ(camera.eye, glm::vec3(1, 2, 5));

  // Without zfar, an infinite projection (§3.10.3: −1 and −2 znear in the third row and column).
  perspective.zfar = 0;
  const Camera infinite = scene_camera(perspective, world, 0.5);
  EXPECT_NEAR(ndc(infinite, {1 + 0.5 * half_height, 2, 0}).x, 1, 1e-5);
  EXPECT_FLOAT_EQ(infinite.projection[2][3], -1.0f);
  EXPECT_FLOAT_EQ(infinite.projection[3][2], -1.0f);
  EXPECT_LT(ndc(infinite, {1, 2, -1e6}).z, 1.0) << "nothing is beyond the far plane";
}

TEST(SceneCamera, ScaleInTheNodeMatrixDoesNotChangeTheView) {
  SceneCamera perspective;
  perspective.yfov = 0.6;
  perspective.znear = 0.1;
  const Mat4<double> turned = glm::rotate(Mat4<double>(1.0), 0.3, glm::dvec3(0, 1, 0));
  Mat4<double> placed = turned;
  placed[3] = {2, 0, 7, 1};
  Mat4<double> scaled = glm::scale(placed, glm::dvec3(3, 0.5, 2));
  const Camera a = scene_camera(perspective, placed, 1.5), b = scene_camera(perspective, scaled, 1.5);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a.view[c][r], b.view[c][r], 1e-6) << c << "," << r;
  Mat4<double> flat = placed;
  flat[2] = glm::dvec4(0.0);  // zero scale along z: no viewing direction
  EXPECT_THROW(scene_camera(perspective, flat, 1.0), InputError);
}

TEST(SceneCamera, OrthographicShowsYmagAndTheImagesWidth) {
  SceneCamera ortho;
  ortho.orthographic = true;
  ortho.xmag = 2;
  ortho.ymag = 1;
  ortho.znear = 0;
  ortho.zfar = 10;
  Mat4<double> world(1.0);
  world[3] = {0, 0, 5, 1};
  const Camera camera = scene_camera(ortho, world, 2.0);  // the camera's own 2:1
  const glm::dvec3 corner = ndc(camera, {2, 1, -3});
  EXPECT_NEAR(corner.x, 1, 1e-6);
  EXPECT_NEAR(corner.y, 1, 1e-6);
  EXPECT_NEAR(ndc(camera, {-2, -1, 2}).x, -1, 1e-6);
  // A square image keeps ymag and shows as much width: x = 1 at the edge.
  EXPECT_NEAR(ndc(scene_camera(ortho, world, 1.0), {1, 1, 0}).x, 1, 1e-6);
}

TEST(SceneCamera, InvalidCameraAndUnknownNodeAreInputErrors) {
  SceneCamera wide;
  wide.yfov = 3.2;  // more than π
  wide.znear = 0.1;
  EXPECT_THROW(scene_camera(wide, Mat4<double>(1.0), 1.0), InputError);
  SceneCamera far_away;  // finite in double, not in float: −2 znear overflows
  far_away.yfov = 0.5;
  far_away.znear = 1e200;
  EXPECT_THROW(scene_camera(far_away, Mat4<double>(1.0), 1.0), InputError);
  SceneCamera broken;
  broken.problem = "camera 0: znear must be above 0; it cannot be rendered through";
  try {
    scene_camera(broken, Mat4<double>(1.0), 1.0);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), broken.problem);
  }

  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/camera_dolly.gltf");
  EXPECT_EQ(asset.nodes[size_t(find_camera_node(asset, "dolly"))].name, "dolly");
  EXPECT_EQ(asset.cameras[size_t(asset.nodes[size_t(find_camera_node(asset, "top"))].camera)].orthographic, true);
  try {
    find_camera_node(asset, "arm");  // a node, but without a camera
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--camera 'arm': no node of that name has a camera (camera nodes: 'dolly', 'top')");
  }
}

}  // namespace
}  // namespace dqskin
