// An encoded image's size in pixels as its header declares it, without decoding it (internal to the
// loader's memory estimate): PNG's IHDR, JPEG's start-of-frame, WebP's VP8, VP8L or VP8X header.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>

namespace dqskin::gltf {

// {width, height}, or nothing when the bytes are none of these formats or their header is cut short.
// Reads only inside `bytes`.
std::optional<std::pair<uint32_t, uint32_t>> declared_image_size(std::span<const uint8_t> bytes);

}  // namespace dqskin::gltf
