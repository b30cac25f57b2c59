// The heights roughing cuts at: every step-down from the material's top, and every flat face of the part plus the
// allowance. A level only at the step-downs leaves up to a whole step-down on a flat face above its level (the
// cube roughed in 3 mm steps kept 2 mm on its top, four times the 0.5 mm asked for); a level at the face's height
// plus the allowance leaves the allowance.
#pragma once
#include <cstddef>
#include <vector>

#include "rosmill/plan/plan_support.hpp"

namespace rosmill::core {

// The heights shared by at least `min_count` of the sampled cutter-location heights (equal within 1e-6 mm),
// highest first: a flat end or ball over a flat face gives the same CL height everywhere on it, a curved or
// scanned surface never repeats one. Heights at or below `floor` are left out (the floor has its own level).
std::vector<double> flat_heights(std::vector<double> cl_heights, size_t min_count, double floor);

// The heights of the part's flat faces plus the allowance, highest first: cutter locations dropped on a grid
// (spacing R/2, at least 0.5 mm) whose height equals their neighbours' along both the row and the column (an
// inclined face level along one of them, or a symmetric part's equal heights far apart, is no flat face).
std::vector<double> flat_face_heights(const Surface& surface, const PlanFrame& frame);

// Levels below `top`, highest first: top - k * stepdown above `floor`, every flat height between `floor` and `top`,
// and `floor` itself. A step-down level within `merge` mm above a flat level is dropped (the flat level cuts it).
std::vector<double> roughing_levels(double top, double floor, double stepdown, const std::vector<double>& flats,
                                    double merge = 0.05);

}  // namespace rosmill::core
