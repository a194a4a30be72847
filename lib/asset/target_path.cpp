// The spelling of an animation channel's path (dqskin/asset.hpp), shared by the loader's messages and the
// diff's clip matching.
#include "dqskin/asset.hpp"

namespace dqskin {

const char* target_path_name(TargetPath path) {
  switch (path) {
    case TargetPath::kTranslation: return "translation";
    case TargetPath::kRotation: return "rotation";
    case TargetPath::kScale: return "scale";
    case TargetPath::kWeights: return "weights";
  }
  return "?";
}

}  // namespace dqskin
