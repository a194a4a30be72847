// The contact sheet of a clip's worst frames (internal to lib/report): each frame drawn with the
// mode-diff shading (|lbs − dqs| per vertex as a heat map on the dqs surface), side by side under one
// camera, with a legend panel whose color bar is labelled in scene units, so that the PNG read alone
// says what its colors mean.
#pragma once

#include "dqskin/asset.hpp"
#include "dqskin/gpu_context.hpp"
#include "dqskin/renderer.hpp"
#include "dqskin/skinning.hpp"

#include <vector>

namespace dqskin::report_detail {

struct WorstFrames {
  const Asset& asset;
  const std::vector<MeshInstance>& instances;
  const Clip* clip = nullptr;
  std::vector<double> times;  // the frames to draw, in order
  double scale = 0;           // the distance the top color stands for, scene units (> 0 for any color)
  int cell = 320;             // each frame's render, pixels square
};

// Deforms the frames with lbs and dqs on the CPU reference and draws the sheet. `context` draws.
Image worst_frames_sheet(GpuContext& context, const WorstFrames& frames);

}  // namespace dqskin::report_detail
