// The material the stock leaves above the design at given places, as seen from a setup: for each point (workpiece
// frame), the stock's top minus the design's over the point's cell of the setup's view. A view of the job for
// people (the stock coloured by what is left on the part), not a check: the verifier and the job report measure.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/stock/in_process_stock.hpp"

namespace rosmill::core::stock {

// NaN for a point whose cell holds no material or lies outside the view.
std::vector<float> material_left_at(const InProcessStock& stock, const Mesh& design, const SetupFrame& setup,
                                    const std::vector<Vec3>& points);

}  // namespace rosmill::core::stock
