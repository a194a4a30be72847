// The integer values that glTF 2.0's JSON schema constrains, checked on the JSON before tinygltf reads it
// (internal to the loader). tinygltf passes over what it cannot use: an index of 4.5 or an accessor
// byteOffset of −12 becomes the default, an index beyond 32 bits is truncated to int. So every such value
// is checked here, by type (an integer, written without a fraction), sign and range, or set of allowed
// values (componentType, mode, sampler enums), core and the extensions dqskin reads or copies.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace dqskin::gltf {

// Checks `doc` (a glTF document) against every rule. A bad value in the structure, geometry, skins or
// animation throws InputError naming it ("accessor 3: byteOffset -12 must be an integer of at least 0").
// A bad value in appearance (materials, textures, samplers, and the references to them and to cameras and
// lights) is removed from `doc` with a warning saying what happens instead (docs/DESIGN.md §5.3:
// broken appearance is dropped with a warning); returns those warnings, ordered by where they are
// (top-level array, index, property).
std::vector<std::string> check_schema_values(nlohmann::json& doc);

}  // namespace dqskin::gltf
