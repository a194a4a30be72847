// KHR_animation_pointer: which JSON pointers animate nodes and meshes, which are other properties, which
// are not pointers to anything a glTF asset defines; and the channels tinygltf drops, restored from the JSON.
#include "animation_pointer.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace dqskin::gltf {
namespace {

using P = PointerProperty;

TEST(AnimationPointer, NamesTheNodeAndMeshPropertiesOrdinaryChannelsAnimate) {
  const std::pair<const char*, P> cases[] = {{"/nodes/0/translation", P::kNodeTranslation},
                                             {"/nodes/3/rotation", P::kNodeRotation},
                                             {"/nodes/12/scale", P::kNodeScale},
                                             {"/nodes/7/weights", P::kNodeWeights},
                                             {"/meshes/5/weights", P::kMeshWeights}};
  for (const auto& [text, property] : cases) {
    const AnimationPointer p = parse_animation_pointer(text);
    EXPECT_EQ(p.property, property) << text;
    EXPECT_TRUE(p.problem.empty()) << text << ": " << p.problem;
  }
  EXPECT_EQ(parse_animation_pointer("/nodes/12/scale").index, 12u);
  EXPECT_EQ(parse_animation_pointer("/meshes/5/weights").index, 5u);
  EXPECT_EQ(parse_animation_pointer("/nodes/999999999/rotation").index, 999999999u);
}

TEST(AnimationPointer, OtherPropertiesAreOtherNotErrors) {
  for (const char* text : {"/materials/0/pbrMetallicRoughness/baseColorFactor", "/cameras/0/perspective/yfov",
                           "/extensions/KHR_lights_punctual/lights/0/intensity",
                           "/nodes/0/extensions/KHR_node_visibility/visible", "/nodes/0/weights/1", "/nodes/0",
                           "/nodes/0/matrix", "/meshes/0/primitives", "/nodes/0/rot~0ation", "/meshes/0/weig~1hts",
                           "/nodes~10/rotation", "/animations/0/channels"}) {
    const AnimationPointer p = parse_animation_pointer(text);
    EXPECT_EQ(p.property, P::kOther) << text;
    EXPECT_TRUE(p.problem.empty()) << text << ": " << p.problem;
  }
}

TEST(AnimationPointer, RefusesWhatIsNotAPointerToAnExistingKindOfProperty) {
  const std::pair<const char*, const char*> cases[] = {
      {"nodes/0/rotation", "does not start with '/'"},
      {"", "does not start with '/'"},
      {"/nodes/0/rot~2", "has '~' not followed by 0 or 1"},
      {"/nodes/0/rot~", "has '~' not followed by 0 or 1"},
      {"/nodes/01/rotation", "names node '01', which is not an array index"},
      {"/nodes/-1/rotation", "names node '-1', which is not an array index"},
      {"/nodes/x/scale", "names node 'x', which is not an array index"},
      {"/nodes//scale", "names node '', which is not an array index"},
      {"/meshes/1234567890/weights", "names mesh '1234567890', which is not an array index"}};
  for (const auto& [text, problem] : cases) EXPECT_EQ(parse_animation_pointer(text).problem, problem) << text;
}

TEST(AnimationPointer, RestoresTheChannelsTinygltfDropsInTheirOrder) {
  const nlohmann::json doc = nlohmann::json::parse(R"({"animations": [{"channels": [
      {"sampler": 0, "target": {"node": 1, "path": "rotation"}},
      {"sampler": 1, "target": {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": "/nodes/2/scale"}}}},
      {"sampler": 2, "target": {"path": "translation"}},
      {"sampler": 3, "target": {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": 7}}}}]}]})");
  tinygltf::Model model;
  model.animations.resize(1);
  model.animations[0].channels.resize(1);  // what tinygltf keeps: the channel with a node
  restore_channels(model, doc);
  const std::vector<tinygltf::AnimationChannel>& c = model.animations[0].channels;
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].target_node, 1);
  EXPECT_EQ(c[0].target_path, "rotation");
  EXPECT_EQ(channel_pointer(c[0]), nullptr);
  EXPECT_EQ(c[1].sampler, 1);
  EXPECT_EQ(c[1].target_node, -1);
  EXPECT_EQ(c[1].target_path, "pointer");
  ASSERT_NE(channel_pointer(c[1]), nullptr);
  EXPECT_EQ(*channel_pointer(c[1]), "/nodes/2/scale");
  EXPECT_EQ(c[2].target_node, -1);  // no node: ignored (§3.11), but still channel 2
  EXPECT_EQ(c[2].target_path, "translation");
  EXPECT_EQ(c[3].sampler, 3);
  EXPECT_EQ(channel_pointer(c[3]), nullptr);  // not a string
}

}  // namespace
}  // namespace dqskin::gltf
