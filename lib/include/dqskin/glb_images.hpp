// Where the images of baked .glb frames go: a bake option (BakeOptions::glb_images) that the glb writer
// carries out.
#pragma once

#include <string>

namespace dqskin {

// Where the images of .glb frames go (bake --glb-images, docs/formats.md, "Bake outputs").
enum class GlbImages {
  kEmbed,   // in every frame's BIN chunk: each frame stands alone, and repeats every image
  kShared,  // once, as files beside the frames (GlbWriter::image_files), which every frame references by a
            // relative URI (glTF 2.0 §3.8.3: a .glb may reference external images)
  kNone,    // left out, with the textures and samplers that use them: materials keep their factors
};

// "embed", "shared", "none" → the mode. Throws InputError naming the flag for another name.
GlbImages parse_glb_images(const std::string& name);
const char* to_string(GlbImages images);

}  // namespace dqskin
