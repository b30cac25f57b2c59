// Which face a section chain continues into when it leaves a face through one of its edges.
//
// Half-edge h = 3 * face + corner (the edge from corner to corner + 1). links[h] is the half-edge of the face the
// chain enters next, or kNone where the chain must end (an open edge, or the odd face out at a non-manifold
// edge). The relation is symmetric and does not depend on the plane: every face of a crossing edge crosses.
#pragma once
#include <vector>

#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core::slice_detail {

// Manifold edges link their two faces. At a non-manifold edge the faces are sorted by angle around the edge and
// paired across the wedges of material (between a face whose normal points back and the next one whose normal
// points on), so that solids touching along an edge get a closed section each; when the orientation does not
// alternate, neighbours in angle are paired. Both keep the chains closed and as few as the topology allows.
std::vector<uint32_t> build_edge_links(const Mesh& mesh);

}  // namespace rosmill::core::slice_detail
