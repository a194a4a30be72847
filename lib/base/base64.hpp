// Base64 (RFC 4648 section 4: the standard alphabet, with padding) for data URIs: the PNGs that the HTML
// page of `dqskin report` embeds, and the buffers of the glTF files that tests write.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace dqskin::io {

// `bytes` as base64 text, padded with '=' to a multiple of 4 characters, no line breaks.
std::string base64(std::span<const uint8_t> bytes);

}  // namespace dqskin::io
