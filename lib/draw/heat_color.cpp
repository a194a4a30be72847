#include "heat_color.hpp"

#include <algorithm>

namespace dqskin {

glm::vec3 heat_color(float t) {
  static const glm::vec3 stops[4] = {{0.02f, 0.02f, 0.25f}, {0.0f, 0.6f, 0.8f}, {1.0f, 0.85f, 0.0f}, {0.8f, 0.0f, 0.0f}};
  t = std::clamp(t, 0.0f, 1.0f);
  const float x = t * 3.0f;
  const int i = std::min(int(x), 2);
  return glm::mix(stops[i], stops[i + 1], x - float(i));
}

}  // namespace dqskin
