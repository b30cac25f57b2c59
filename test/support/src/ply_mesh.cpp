#include "rosmill/testing/ply_mesh.hpp"

#include <vector>

#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include "rosmill/error.hpp"

namespace rosmill::core {

Mesh read_ply_mesh(const std::string& path, double scale) {
  pcl::PolygonMesh polygons;
  if (pcl::io::loadPLYFile(path, polygons) != 0) throw Error(path, "PCL cannot read it as a PLY mesh");
  pcl::PointCloud<pcl::PointXYZ> vertices;
  pcl::fromPCLPointCloud2(polygons.cloud, vertices);
  std::vector<Vec3> corners;
  for (const pcl::Vertices& face : polygons.polygons) {
    if (face.vertices.size() != 3) continue;
    for (const uint32_t v : face.vertices) {
      if (v >= vertices.size()) throw Error(path, "a face names a vertex past the last");
      corners.push_back(scale * Vec3(vertices[v].x, vertices[v].y, vertices[v].z));
    }
  }
  if (corners.empty()) throw Error(path, "holds no triangle");
  return build_mesh(corners);
}

}  // namespace rosmill::core
