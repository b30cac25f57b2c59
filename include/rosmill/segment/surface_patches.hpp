// Phase 1 of the segmentation (Lefebvre & Lauwers, "STL Model Segmentation for Multi-Axis Machining Operations
// Planning", section 3.2.2): sharp-edge "surface flooding" of a mesh into surface
// patches, then the recombination step that merges patches too small to machine into their dominant neighbour.
//
// A facet joins its neighbour's patch across an edge when the length of the difference of the two unit normals
// is below the threshold (0.4 by default, about 23 degrees). The rule is tested per edge, so a facet rejected
// through one edge still joins through another (the paper's figures 6 and 7): a patch is a connected component
// of the facets over the edges that pass. Zero-area facets have no normal: they join a neighbour's patch and
// never make patches of their own.
//
// The result only refers to the mesh (which is const and never copied), so several setups' segmentations
// (setup_segmentation.hpp) can be built over the same patches and exist together.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core::segment {

// When a patch (or a phase 2 segment) counts as too small to machine on its own.
struct SizeRule {
  enum class Kind { FacetCount, AreaFraction };
  Kind kind = Kind::AreaFraction;
  // Kind::FacetCount: patches with fewer facets than this merge.
  size_t min_facets = 0;
  // Kind::AreaFraction: patches whose area is below this fraction of the mesh's area merge.
  double min_area_fraction = 1e-4;
};

struct SegmentOptions {
  // Largest length of the difference of two unit normals (0..2) across an edge inside one patch.
  double threshold = 0.4;
  SizeRule small;
};

// A closed (or, on a broken mesh, open) chain of vertex indices around a patch, in the facets' winding order.
struct BoundaryLoop {
  std::vector<uint32_t> vertices;
  bool closed = true;
  // True when every edge of the loop is an open edge of the mesh (a hole, the rim of an open surface).
  bool mesh_border = false;
};

struct Patch {
  uint32_t id = 0;
  // This patch's facets are facet_order[first_facet, first_facet + facet_count) of its SurfacePatches.
  uint32_t first_facet = 0;
  uint32_t facet_count = 0;
  double area = 0.0;
  // Area-weighted mean of the facet normals, unit length (zero when the normals cancel or the area is zero).
  Vec3 normal = Vec3::Zero();
  // Ids of the patches sharing at least one edge with this one, ascending.
  std::vector<uint32_t> neighbours;
  std::vector<BoundaryLoop> loops;
};

// What the segmentation noticed about the mesh (an open or non-manifold mesh is segmented all the same).
struct MeshNotes {
  size_t open_edges = 0;
  size_t nonmanifold_edges = 0;
  size_t inconsistent_edges = 0;  // manifold edges whose two facets disagree in orientation
  size_t degenerate_facets = 0;
  size_t patches_before_recombination = 0;
};

class SurfacePatches {
 public:
  const Mesh& mesh() const { return *mesh_; }
  const SegmentOptions& options() const { return options_; }
  size_t count() const { return patches_.size(); }
  const std::vector<Patch>& patches() const { return patches_; }
  const Patch& patch(size_t id) const { return patches_[id]; }
  // Patch id of each facet.
  const std::vector<uint32_t>& labels() const { return labels_; }
  uint32_t label(size_t facet) const { return labels_[facet]; }
  // Facet indices grouped by patch (see Patch::first_facet).
  const std::vector<uint32_t>& facet_order() const { return facet_order_; }
  const uint32_t* facets_begin(const Patch& p) const { return facet_order_.data() + p.first_facet; }
  const uint32_t* facets_end(const Patch& p) const { return facets_begin(p) + p.facet_count; }
  // For the facet at position i of facet_order: the positions of the facets across its edges 0, 1, 2 (corner k
  // to k+1) when they lie in the same patch over a manifold edge, kNone otherwise. Made once here so that every
  // setup's phase 2 floods a patch through cache-local positions instead of the mesh's edge table.
  const std::vector<std::array<uint32_t, 3>>& inner_neighbours() const { return inner_neighbours_; }
  // Edges that may separate two patches: every edge the flood did not cross (sharp, open, non-manifold).
  const std::vector<uint32_t>& cut_edges() const { return cut_edges_; }
  double total_area() const { return total_area_; }
  const MeshNotes& notes() const { return notes_; }

 private:
  friend SurfacePatches segment_surface(const Mesh& mesh, const SegmentOptions& options);
  const Mesh* mesh_ = nullptr;
  SegmentOptions options_;
  std::vector<Patch> patches_;
  std::vector<uint32_t> labels_;
  std::vector<uint32_t> facet_order_;
  std::vector<std::array<uint32_t, 3>> inner_neighbours_;
  std::vector<uint32_t> cut_edges_;
  double total_area_ = 0.0;
  MeshNotes notes_;
};

// Phase 1: flood and recombine. The mesh must outlive the result. Throws Error for a threshold outside (0, 2]
// or a negative size.
SurfacePatches segment_surface(const Mesh& mesh, const SegmentOptions& options = {});

}  // namespace rosmill::core::segment
