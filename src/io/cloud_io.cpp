// Point clouds through PCL. Files are read into PCL's untyped PCLPointCloud2 and x, y, z are taken from it with
// their stored type (float or double: Open3D writes PLY doubles), so no field layout is assumed.
#include "rosmill/io/cloud_io.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include "cloud_format.hpp"
#include "cloud_header_check.hpp"
#include "file_bytes.hpp"
#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"

namespace rosmill::core {
namespace {

const pcl::PCLPointField* find_field(const pcl::PCLPointCloud2& cloud, const char* name) {
  for (const auto& f : cloud.fields)
    if (f.name == name) return &f;
  return nullptr;
}

template <class T>
double load_as(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return static_cast<double>(v);
}

double load_value(const uint8_t* p, uint8_t type) {
  switch (type) {
    case pcl::PCLPointField::FLOAT32: return load_as<float>(p);
    case pcl::PCLPointField::FLOAT64: return load_as<double>(p);
    case pcl::PCLPointField::INT8: return load_as<int8_t>(p);
    case pcl::PCLPointField::UINT8: return load_as<uint8_t>(p);
    case pcl::PCLPointField::INT16: return load_as<int16_t>(p);
    case pcl::PCLPointField::UINT16: return load_as<uint16_t>(p);
    case pcl::PCLPointField::INT32: return load_as<int32_t>(p);
    case pcl::PCLPointField::UINT32: return load_as<uint32_t>(p);
  }
  return std::nan("");
}

size_t type_size(uint8_t type) {
  switch (type) {
    case pcl::PCLPointField::INT8:
    case pcl::PCLPointField::UINT8: return 1;
    case pcl::PCLPointField::INT16:
    case pcl::PCLPointField::UINT16: return 2;
    case pcl::PCLPointField::INT32:
    case pcl::PCLPointField::UINT32:
    case pcl::PCLPointField::FLOAT32: return 4;
    case pcl::PCLPointField::FLOAT64: return 8;
  }
  return 0;
}

void read_blob(const std::string& path, const std::string& format, pcl::PCLPointCloud2& blob) {
  // PCL prints a warning for every element it does not read (a PLY mesh's faces); only the points are wanted,
  // and real problems come back as a return code turned into an Error below.
  pcl::console::setVerbosityLevel(pcl::console::L_ERROR);
  int rc = -1;
  try {
    if (format == "pcd") {
      pcl::PCDReader reader;
      rc = reader.read(path, blob);
    } else {
      pcl::PLYReader reader;
      rc = reader.read(path, blob);
    }
  } catch (const std::exception& e) {
    throw Error(path, "cannot read " + format + " file: " + e.what());
  }
  if (rc < 0) throw Error(path, "cannot read " + format + " file (malformed header or data)");
}

}  // namespace


PointCloud read_cloud(const std::string& path, const CloudReadOptions& options, CloudInfo* info) {
  check_input_file(path);
  const std::string format = io::cloud_format(path);
  {
    const io::FileBytes bytes(path);
    if (bytes.gzipped()) throw Error(path, "compressed point cloud files are not supported (gunzip it first)");
    if (format == "pcd")
      io::check_pcd_layout(bytes.data(), bytes.size(), path);
    else
      io::check_ply_layout(bytes.data(), bytes.size(), path);
  }
  pcl::PCLPointCloud2 blob;
  read_blob(path, format, blob);

  const pcl::PCLPointField* axes[3] = {find_field(blob, "x"), find_field(blob, "y"), find_field(blob, "z")};
  for (int k = 0; k < 3; ++k)
    if (!axes[k]) throw Error(path, std::string("the points have no '") + "xyz"[k] + "' field");
  const size_t n = static_cast<size_t>(blob.width) * blob.height;
  // The data size is checked against the header rather than trusted: a short file must not be read past.
  for (int k = 0; k < 3; ++k)
    if (type_size(axes[k]->datatype) == 0 || axes[k]->offset + type_size(axes[k]->datatype) > blob.point_step)
      throw Error(path, std::string("field '") + "xyz"[k] + "' has an unsupported type or layout");
  if (n > 0 && (blob.point_step == 0 || blob.data.size() / blob.point_step < n))
    throw Error(path, "point data shorter than the header's " + std::to_string(n) + " points");

  const double scale = mm_per_unit(options.units);
  PointCloud cloud;
  cloud.points.reserve(n);
  size_t dropped = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* point = blob.data.data() + i * blob.point_step;
    // Judged in millimetres: a coordinate near the largest double in metres is infinite once scaled.
    const Vec3 p = scale * Vec3(load_value(point + axes[0]->offset, axes[0]->datatype),
                                load_value(point + axes[1]->offset, axes[1]->datatype),
                                load_value(point + axes[2]->offset, axes[2]->datatype));
    if (!p.allFinite()) {
      ++dropped;
      continue;
    }
    cloud.points.push_back(p);
  }
  if (n == 0) throw Error(path, "empty point cloud (no points)");
  if (cloud.points.empty())
    throw Error(path, "no finite point: all " + std::to_string(n) + " points are NaN or infinite");
  cloud.recompute_bbox();
  if (info) {
    info->format = format;
    info->points_in_file = n;
    info->dropped_nonfinite = dropped;
  }
  return cloud;
}

}  // namespace rosmill::core
