// Points drawn on a mesh's surface, area-weighted (a uniform density over the surface, whatever the tessellation),
// with the face's outward normal: the design as a scanner would see it, and the target of point-to-plane ICP.
#pragma once
#include <cstdint>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core::scan {

struct SurfaceSample {
  std::vector<Vec3> points;
  std::vector<Vec3> normals;    // the unit normal of the face each point lies on
  std::vector<uint32_t> faces;  // that face
};

// `count` points, the same for the same mesh, count and seed. Throws Error when the mesh has no area or count is 0.
SurfaceSample sample_surface(const Mesh& mesh, size_t count, uint64_t seed = 1);

}  // namespace rosmill::core::scan
