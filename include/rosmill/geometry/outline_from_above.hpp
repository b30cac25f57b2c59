// The outline of a mesh seen from above (down -Z): the closed contours of its plan-view silhouette, the region
// under which some part of the surface lies. The inspection and deviation maps draw it so a reader sees where the
// part is.
#pragma once
#include <vector>

#include "rosmill/geometry/contour.hpp"
#include "rosmill/geometry/mesh.hpp"

namespace rosmill::core {

// The union of the mesh's triangles projected onto XY (outer contours counter-clockwise, holes clockwise). Every
// triangle counts whichever way it faces, so an open surface (a relief, a scanned shell) gets its whole silhouette,
// not only the part its upward faces cover; vertical faces cover no area and drop out.
std::vector<Contour> outline_from_above(const Mesh& mesh);

}  // namespace rosmill::core
