#include "rosmill/geometry/primitives.hpp"

#include <cmath>

#include "rosmill/error.hpp"

namespace rosmill::core {
namespace {

// Triangles are appended counter-clockwise seen from outside, so normals point out of the solid.
void tri(std::vector<Vec3>& out, const Vec3& a, const Vec3& b, const Vec3& c) {
  out.push_back(a);
  out.push_back(b);
  out.push_back(c);
}

// Outward quad a-b-c-d (counter-clockwise from outside) as two triangles.
void quad(std::vector<Vec3>& out, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  tri(out, a, b, c);
  tri(out, a, c, d);
}

// Point k of n on a circle of radius r at height z. Every use of a circle point goes through here so that
// shared vertices are bit-identical and weld exactly.
Vec3 circle_point(double r, double z, int k, int n) {
  const double a = 2.0 * M_PI * (k % n) / n;
  return Vec3(r * std::cos(a), r * std::sin(a), z);
}

// Point of a sphere of radius r centred at `c`, ring `ring` of `rings` (0 = pole at c + pole_sign * r),
// segment k of n. Ring `rings` lies on the equator.
Vec3 sphere_point(const Vec3& c, double r, double pole_sign, int ring, int rings, int k, int n) {
  if (ring == 0) return c + Vec3(0, 0, pole_sign * r);
  // The equator lies exactly in the plane of the centre (cos(pi/2) is not exactly 0 in floating point), so
  // that the flat faces meeting it are exactly planar.
  if (ring == rings) return c + circle_point(r, 0.0, k, n);
  const double polar = 0.5 * M_PI * ring / rings;
  const Vec3 p = circle_point(r * std::sin(polar), 0.0, k, n);
  return c + Vec3(p.x(), p.y(), pole_sign * r * std::cos(polar));
}

constexpr int kRoundSegments = 36;     // cylinder and cone: 144 and 72 triangles
constexpr int kSphereSegments = 30;    // dome and cavity
constexpr int kDomeRings = 15;         // 2 * 30 * 15 = 900 triangles
constexpr int kCavityRings = 13;       // 30 + 2 * 30 * 12 pocket + 150 block = 900 triangles
constexpr double kCavityBlockRadius = 60.0;
constexpr double kCavityBlockHeight = 60.0;

}  // namespace

std::vector<Vec3> cube_corners(double s) {
  std::vector<Vec3> out;
  const Vec3 p[8] = {{0, 0, 0}, {s, 0, 0}, {s, s, 0}, {0, s, 0}, {0, 0, s}, {s, 0, s}, {s, s, s}, {0, s, s}};
  quad(out, p[0], p[3], p[2], p[1]);  // bottom, facing -Z
  quad(out, p[4], p[5], p[6], p[7]);  // top
  quad(out, p[0], p[1], p[5], p[4]);  // -Y
  quad(out, p[1], p[2], p[6], p[5]);  // +X
  quad(out, p[2], p[3], p[7], p[6]);  // +Y
  quad(out, p[3], p[0], p[4], p[7]);  // -X
  return out;
}

std::vector<Vec3> box_corners(const Box3& b) {
  const Vec3 s = b.size();
  std::vector<Vec3> out = cube_corners(1.0);
  for (Vec3& p : out) p = b.min + p.cwiseProduct(s);
  return out;
}

std::vector<Vec3> cylinder_corners(double r, double h) {
  std::vector<Vec3> out;
  const int n = kRoundSegments;
  const Vec3 bottom(0, 0, 0), top(0, 0, h);
  for (int k = 0; k < n; ++k) {
    const Vec3 b0 = circle_point(r, 0, k, n), b1 = circle_point(r, 0, k + 1, n);
    const Vec3 t0 = circle_point(r, h, k, n), t1 = circle_point(r, h, k + 1, n);
    quad(out, b0, b1, t1, t0);
    tri(out, top, t0, t1);
    tri(out, bottom, b1, b0);
  }
  return out;
}

std::vector<Vec3> cone_corners(double r, double h) {
  std::vector<Vec3> out;
  const int n = kRoundSegments;
  const Vec3 apex(0, 0, h), bottom(0, 0, 0);
  for (int k = 0; k < n; ++k) {
    const Vec3 b0 = circle_point(r, 0, k, n), b1 = circle_point(r, 0, k + 1, n);
    tri(out, b0, b1, apex);
    tri(out, bottom, b1, b0);
  }
  return out;
}

std::vector<Vec3> dome_corners(double r) {
  std::vector<Vec3> out;
  const int n = kSphereSegments, rings = kDomeRings;
  const Vec3 c(0, 0, 0);
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < rings; ++i) {
      const Vec3 a0 = sphere_point(c, r, 1, i, rings, k, n), a1 = sphere_point(c, r, 1, i, rings, k + 1, n);
      const Vec3 b0 = sphere_point(c, r, 1, i + 1, rings, k, n), b1 = sphere_point(c, r, 1, i + 1, rings, k + 1, n);
      if (i == 0)
        tri(out, a0, b0, b1);  // fan around the pole
      else
        quad(out, a0, b0, b1, a1);
    }
    // The base disc, a fan from the centre.
    tri(out, c, sphere_point(c, r, 1, rings, rings, k + 1, n), sphere_point(c, r, 1, rings, rings, k, n));
  }
  return out;
}

std::vector<Vec3> cavity_corners(double r) {
  std::vector<Vec3> out;
  const int n = kSphereSegments, rings = kCavityRings;
  const double R = std::max(kCavityBlockRadius, r + 10.0), H = std::max(kCavityBlockHeight, r + 10.0);
  const Vec3 c(0, 0, H), bottom(0, 0, 0);
  for (int k = 0; k < n; ++k) {
    // The pocket: a hemisphere opening upwards whose faces look at the centre c (out of the solid, into the
    // empty pocket). Mirroring the dome's rings in z flips their winding, which is what turns them inwards.
    for (int i = 0; i < rings; ++i) {
      const Vec3 a0 = sphere_point(c, r, -1, i, rings, k, n), a1 = sphere_point(c, r, -1, i, rings, k + 1, n);
      const Vec3 b0 = sphere_point(c, r, -1, i + 1, rings, k, n), b1 = sphere_point(c, r, -1, i + 1, rings, k + 1, n);
      if (i == 0)
        tri(out, a0, b0, b1);
      else
        quad(out, a0, b0, b1, a1);
    }
    const Vec3 rim0 = sphere_point(c, r, -1, rings, rings, k, n), rim1 = sphere_point(c, r, -1, rings, rings, k + 1, n);
    const Vec3 o0 = circle_point(R, H, k, n), o1 = circle_point(R, H, k + 1, n);
    const Vec3 b0 = circle_point(R, 0, k, n), b1 = circle_point(R, 0, k + 1, n);
    quad(out, rim0, o0, o1, rim1);  // top annulus between the rim and the outer edge
    quad(out, b0, b1, o1, o0);      // outer wall
    tri(out, bottom, b1, b0);       // bottom
  }
  return out;
}

const std::vector<std::string>& primitive_names() {
  static const std::vector<std::string> names = {"cube", "cylinder", "dome", "cone", "cavity"};
  return names;
}

Mesh make_primitive(const std::string& name) {
  if (name == "cube") return build_mesh(cube_corners());
  if (name == "cylinder") return build_mesh(cylinder_corners());
  if (name == "dome") return build_mesh(dome_corners());
  if (name == "cone") return build_mesh(cone_corners());
  if (name == "cavity") return build_mesh(cavity_corners());
  throw Error("primitive", "unknown primitive '" + name + "' (expected cube, cylinder, dome, cone or cavity)");
}

}  // namespace rosmill::core
