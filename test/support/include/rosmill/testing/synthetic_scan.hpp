// A synthetic scanner for the tests and benchmarks of registration, fusion and inspection: points drawn on the
// design's surface (area-weighted), kept where the surface faces the sensor (back faces culled; no occlusion by
// other parts of the surface), with isotropic Gaussian noise; and random rigid poses from fixed seeds.
#pragma once
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"

namespace rosmill::core::synthetic {

// The points (design frame, mm) of `samples` surface samples that some sensor in `sensors` (positions, design
// frame) faces, each moved by noise of standard deviation `noise` mm per axis. With `max_incidence_deg` below 90
// a sensor sees only surface whose normal lies within that angle of the line to it (a real scanner gets no return
// from grazing faces: from above, a plate's side walls and a pocket's walls are not seen).
PointCloud synthetic_scan(const Mesh& design, const std::vector<Vec3>& sensors, size_t samples, double noise,
                          uint64_t seed, double max_incidence_deg = 90);

// A uniformly random rotation (a normalised Gaussian quaternion) and a translation uniform in
// [-max_translation, max_translation]^3.
Eigen::Matrix4d random_rigid(std::mt19937_64& rng, double max_translation);

// A small rigid error: a turn of `deg` degrees about `axis` (through the origin) and `mm` along it.
Eigen::Matrix4d nudge(double mm, double deg, const Vec3& axis);

// How far a pose error moves the design: the largest displacement of its box's corners (mm).
double box_corner_error(const Mesh& design, const Eigen::Matrix4d& error);

// Sensors above the part: straight above its centre and `oblique` more at 45 degrees around it, at `distance`
// from the centre of the design's box.
std::vector<Vec3> sensors_above(const Mesh& design, int oblique, double distance);

// The pose of a sensor at `position` looking at `target`: its frame's z axis along the line of sight, its x axis
// level (across the line of sight and the world's z; x itself when the sensor looks straight down or up).
Eigen::Matrix4d sensor_pose(const Vec3& position, const Vec3& target);

}  // namespace rosmill::core::synthetic
