// The nodes a bake's sockets and root motion name (internal to lib/bake), found when an input is planned so
// that a name no node has fails that input before anything of it is written (docs/DESIGN.md §3.11).
#pragma once

#include "dqskin/bake.hpp"
#include "../job/job_plan.hpp"

#include <string>
#include <vector>

namespace dqskin::bake_detail {

struct MotionNodes {
  std::vector<int> sockets;  // node indices, in the order --sockets names them
  int root = -1;             // the root whose ground motion is taken out; -1: none
};

// The node called `name`, or node N for "#N". Throws InputError starting with `flag` when no node, or more
// than one, has that name.
int find_named_node(const Asset& asset, const std::string& name, const std::string& flag);

// The root of --root-motion in-place: --root-joint's node, else the first skin's `skeleton` when it is an
// ancestor (or itself) of every joint of that skin, else that skin's topmost joint which is. Throws
// InputError when there is none, or when the root is not an ancestor (or itself) of every joint of every
// skin the scene's instances use.
int choose_root(const InputPlan& input, const std::string& root_joint);

// Both, for `options`. Throws InputError as find_named_node and choose_root do.
MotionNodes find_motion_nodes(const InputPlan& input, const MotionOptions& options);

// Makes every clip of the input sample in place around `nodes.root` (Clip::in_place_root); nothing when
// there is no root.
void set_in_place(InputPlan& input, const MotionNodes& nodes);

}  // namespace dqskin::bake_detail
