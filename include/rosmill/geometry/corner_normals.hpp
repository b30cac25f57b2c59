// Normals at the corners of each facet, for a surface normal that turns smoothly across a faceted model: at each
// corner, the facets round its vertex that lie within a crease angle of the facet, weighted by their angle at the
// vertex (Thurmer and Wuthrich, "Computing vertex normals from polygonal facets", 1998). A facet across a crease
// (a box's edge) keeps its own normal there, so a sharp edge stays sharp.
#pragma once
#include <array>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

// One unit normal per corner of each facet (zero for a degenerate facet).
std::vector<std::array<Vec3, 3>> corner_normals(const Mesh& mesh, double crease_deg = 30.0);

// The normal at barycentric (u, v) of facet f (weights 1 - u - v, u, v on its corners), unit.
Vec3 smooth_normal(const std::vector<std::array<Vec3, 3>>& normals, uint32_t f, double u, double v);

}  // namespace rosmill::core
