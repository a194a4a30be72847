// The picture of a failing clip (internal to lib/diff): A's surface at the clip's worst frame shaded by
// each vertex's distance to B, with the color bar and its scale drawn into the image, so that the file
// read alone says what its colors mean.
#pragma once

#include "diff_side.hpp"

#include "dqskin/camera.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/renderer.hpp"

#include <string>
#include <vector>

namespace dqskin::diff_detail {

struct ErrorHeatMap {
  const DiffSide& side;
  const SideFrame& frame;
  const std::vector<float>& error;  // per vertex of side, scene units
  double top = 0;                   // the error the top of the color bar stands for (the clip's max)
  std::string caption;              // drawn top left ("t = 0.433 s"); only characters of the built-in font
  Bounds framing;                   // the box the camera frames; when empty, the frame's own
};

// Renders the heat map (`size` pixels square, the automatic camera framed on the frame) and draws the
// legend in a panel to its right: a vertical color bar from 0 to `top`, labelled at 0, half and top in
// scene units (glTF's meters); and the caption at the top left. The image is `size` high and wider by
// the panel.
Image render_error_heat_map(GpuContext& context, const ErrorHeatMap& map, int size);

// A file name for a clip's heat map: "<clip>.error.png" with characters other than letters, digits, '-',
// '_' and '.' replaced by '_'.
std::string heat_map_file_name(const std::string& clip);

// Writes the image as an 8-bit sRGB PNG, atomically, replacing an older one. Throws OutputError.
void write_heat_map(const std::string& path, const Image& image);

}  // namespace dqskin::diff_detail
