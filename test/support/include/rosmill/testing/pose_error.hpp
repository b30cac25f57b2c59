// A pose's true error along each degree of freedom a registration or fusion reports (pose_information.hpp): the
// slide of the centre along each principal axis (mm) and the turn about each (degrees), to hold against the stated
// sigmas ("wrong and said certain" is an error beyond 3 sigma).
#pragma once
#include <array>

#include <Eigen/Core>

#include "rosmill/scan/pose_information.hpp"

namespace rosmill::core::synthetic {

// `error` moves the fixed frame onto itself (truth^-1 * found for a design -> scan pose): its components along the
// report's six directions, mm and degrees, in the order of PoseInformation::dofs.
std::array<double, 6> error_by_dof(const scan::PoseInformation& info, const Eigen::Matrix4d& error);

// The largest |error| / sigma over the six directions (0 along a free one: no claim was made).
double worst_sigma_ratio(const scan::PoseInformation& info, const Eigen::Matrix4d& error);

}  // namespace rosmill::core::synthetic
