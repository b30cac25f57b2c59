// A job: one toolpath per tool, in machining order (a single strategy gives one; a multi-stage template such as
// rough, semi-finish and finish gives one per stage). What the post-processor, the verifier and ROS take.
#pragma once
#include <vector>

#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

using Job = std::vector<Toolpath>;

}  // namespace rosmill::core
