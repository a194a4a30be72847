#include "image_files.hpp"
#include "texture_image.hpp"
#include "../base/image_module.hpp"

namespace dqskin {

const ImageFiles& image_files() {
  static const ImageFiles& files = image_module_part<ImageFiles>("dqskin_image_files");
  return files;
}

Image8 decode_texture_image(const EncodedImage& image, size_t index, int max_side) {
  return image_files().decode_texture_image(image, index, max_side);
}

}  // namespace dqskin
