// A triangle mesh from a PLY file (PCL's PLY mesh reader): the real scans of test/data that come as meshes, such as
// the scan-N-plan workshop's part scan, used as a design or as a real surface to scan.
#pragma once
#include <string>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

// Triangles only; `scale` takes the file's units to millimetres (1000 for metres). Throws Error when the file
// cannot be read or holds no triangle.
Mesh read_ply_mesh(const std::string& path, double scale);

}  // namespace rosmill::core
