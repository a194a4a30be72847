// The heat map's colors on the CPU (internal to the image writers): the legend bars drawn beside heat-map
// renders (the geometric diff's error maps, the report's contact sheets) must show the colors that
// glsl/render.frag's heat() gives the surface.
#pragma once

#include <glm/glm.hpp>

namespace dqskin {

// The render's heat colors (glsl/render.frag heat(), unlit): dark blue at 0, cyan, yellow, red at 1.
glm::vec3 heat_color(float t);

}  // namespace dqskin
