// The test primitives of "Tool Path Generation for CNC Milling based on STL Files" (Eng. & Tech. Journal 33(A) 2,
// 2015), generated
// with the paper's exact triangle counts: closed, consistently oriented (normals outward), in millimetres.
#pragma once
#include <string>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

// Corners (3 per triangle) of each primitive; build_mesh() turns them into a Mesh.
std::vector<Vec3> cube_corners(double size = 60.0);                         // 12 triangles, [0,size]^3
std::vector<Vec3> cylinder_corners(double r = 25.0, double h = 60.0);       // 144: 36 segments
std::vector<Vec3> dome_corners(double r = 50.0);                            // 900: hemisphere on z = 0
std::vector<Vec3> cone_corners(double r = 25.0, double h = 60.0);           // 72: 36 segments
std::vector<Vec3> cavity_corners(double r = 50.0);                          // 900: hemispherical pocket in a block
std::vector<Vec3> box_corners(const Box3& box);                             // 12: the box, normals outward

// By name: "cube", "cylinder", "dome", "cone", "cavity"; throws Error for another name.
Mesh make_primitive(const std::string& name);
const std::vector<std::string>& primitive_names();

}  // namespace rosmill::core
