// Samples of a mesh's surface, area-weighted: what the setup choice, the account of the material left on a part
// and the verifier of a multi-axis program measure the surface by.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

// Points on the surface (workpiece frame), each standing for a piece of one facet: a facet larger than spacing^2
// is cut into m x m similar triangles (m = ceil(sqrt(area) / spacing)) sampled at their centroids, a smaller one
// is one sample. The weights of a facet's samples sum to its area.
struct SurfaceSamples {
  std::vector<Vec3> points, normals;
  std::vector<double> weights;  // mm^2
  std::vector<uint32_t> facets;
  size_t size() const { return points.size(); }
};
SurfaceSamples sample_surface(const Mesh& mesh, double spacing);
// A spacing that gives about `target` samples over the mesh's area (never below 0.05 mm).
double sample_spacing(const Mesh& mesh, double target = 40000);

}  // namespace rosmill::core
