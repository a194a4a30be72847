// glTF images decoded for the renderer (internal to lib/draw).
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/image_output.hpp"

namespace dqskin {

// Decodes image `index` of an asset (PNG or JPEG, as §3.8.3 allows; WebP too, which OpenImageIO reads)
// from its bytes into 8-bit RGBA, top row first: glTF's UV (0, 0) is the first pixel of the first row.
// Grey becomes RGB, a missing alpha becomes 255, 16-bit samples are rounded to 8, alpha stays unassociated
// (as glTF stores it). Throws InputError naming the image for missing bytes, a format that is neither,
// a decoding error, a side longer than `max_side` pixels, or more than 8192² pixels (checked from the
// header, before anything is allocated).
Image8 decode_texture_image(const EncodedImage& image, size_t index, int max_side);

}  // namespace dqskin
