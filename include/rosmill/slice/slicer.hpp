// Z slicing of a mesh into closed, oriented, nested contours ("Tool Path Generation for CNC Milling based on STL Files"
// (Eng. & Tech. Journal 33(A) 2, 2015), "The Slicing Process").
//
// A plane z = h meets a triangle where an edge goes from below the plane to above it (the paper's equations 1 and 2
// with the plane's normal along Z). Degenerate cases are decided by one symbolic rule, never by a tolerance: a
// vertex lying exactly on the plane counts as above it, i.e. the section is the limit of sections at h - eps.
// Then every triangle has 0 or 2 crossing edges, every crossing edge is crossed by all of its faces, and the
// segments chain through the mesh's edge adjacency into closed loops wherever the mesh is closed. A plane at
// or below the mesh's Zmin is the exception: it is taken from above (h + eps), so that the bottom outline exists.
// Horizontal faces lying in a plane produce no segments; their area is reported as the layer's flat region.
#pragma once
#include <string>
#include <vector>

#include "rosmill/geometry/contour.hpp"
#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

struct SliceLayer {
  double z = 0.0;
  double flat_area = 0.0;  // mm² of horizontal faces lying exactly in the plane
  std::vector<Contour> contours;
};

struct SliceSummary {
  size_t layers = 0;
  size_t contours = 0;  // closed and open
  size_t open_contours = 0;
  size_t points = 0;
};

// Plane heights, ascending. Each throws Error naming `where` for a non-positive or non-finite argument or an
// empty mesh.
// --step: Zmin + k * step for k = 1 .. floor((Zmax - Zmin) / step) (so the top plane is Zmax when it divides).
std::vector<double> planes_by_step(const Mesh& mesh, double step, const std::string& where = "--step");
// --layers: n planes evenly spaced strictly between Zmin and Zmax: Zmin + k * (Zmax - Zmin) / (n + 1).
std::vector<double> planes_by_count(const Mesh& mesh, int n, const std::string& where = "--layers");
// The paper's accuracy: the fewest evenly spaced planes from Zmin to Zmax whose interval is at most `accuracy`.
std::vector<double> planes_by_accuracy(const Mesh& mesh, double accuracy, const std::string& where = "--accuracy");
// An explicit list, sorted ascending (every value must be finite).
std::vector<double> planes_from_list(std::vector<double> z, const std::string& where = "--z");

// Slices `mesh` at every height of `planes` (ascending); one layer per plane, in the same order. Cost grows as
// O(n log P + output): faces are bucketed by the first plane above their lowest z and each plane visits only the
// faces that cross it. Planes are sliced in parallel (TBB).
std::vector<SliceLayer> slice_mesh(const Mesh& mesh, const std::vector<double>& planes);

SliceSummary summarize(const std::vector<SliceLayer>& layers);

// The paper's export for other CAM tools: "x y z" per line, a blank line between contours (closed contours repeat
// their first point at the end). Throws Error when the file cannot be written.
void write_slices_dat(const std::string& path, const std::vector<SliceLayer>& layers);

// Signed area of a closed polygon (positive when counter-clockwise).
double signed_area(const std::vector<Vec2>& polygon);

}  // namespace rosmill::core
