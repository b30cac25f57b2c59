// Point cloud input through PCL: PCD (ascii, binary, binary_compressed) and PLY (a PLY mesh gives its vertices).
#pragma once
#include <string>

#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/units.hpp"

namespace rosmill::core {

struct CloudReadOptions {
  Units units = Units::Metre;  // ROS custom: clouds are in metres; the cloud comes back in millimetres
};

struct CloudInfo {
  std::string format;        // "pcd" or "ply"
  size_t points_in_file = 0;
  size_t dropped_nonfinite = 0;
};

// Throws Error naming the file when it is missing, unreadable, or holds no finite point.
PointCloud read_cloud(const std::string& path, const CloudReadOptions& options = {}, CloudInfo* info = nullptr);

// Writes a binary PCD of x y z (float) in `units` (metres by default, the ROS custom the reader assumes).
// Throws Error naming the file when the cloud is empty or the file cannot be written.
void write_cloud(const std::string& path, const PointCloud& cloud, Units units = Units::Metre);

// True when the path names a cloud file (.pcd, .ply) rather than a mesh (.stl).
bool is_cloud_path(const std::string& path);
// True when the path names a cloud by its extension or, whatever its name, by its first bytes ("ply", a PCD
// header); false for a missing or unreadable file (the mesh reader then reports it).
bool is_cloud_file(const std::string& path);

}  // namespace rosmill::core
