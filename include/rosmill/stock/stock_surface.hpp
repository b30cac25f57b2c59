// The in-process stock as a closed triangle mesh in the workpiece frame: for rviz, STL, and a look at the part.
// The dexels are sampled as a signed distance along z (to the nearest end of a span, positive in material,
// clamped to a sample step) on a lattice of the export cell, padded by empty samples so that the surface closes,
// and the zero level is extracted by VTK's flying edges (Schroeder, Maynard & Geveci, "Flying edges: a
// high-performance scalable isocontouring algorithm", IEEE LDAV 2015), a marching-cubes variant whose surface is
// closed and manifold. Between a cell with material and one without the surface passes half-way, the side of the
// cell's prism, and along z it passes through the span's ends exactly.
#pragma once
#include <string>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/stock/in_process_stock.hpp"

namespace rosmill::core::stock {

// The largest lattice the export samples (4 bytes a sample): a finer one is refused with the cell that fits.
constexpr size_t kMaxSurfaceSamples = 40'000'000;

// `cell`: the lattice step in mm (0: the stock's own resolution). Throws Error naming `where` when the lattice
// would have more than max_samples samples.
Mesh stock_surface(const InProcessStock& stock, double cell = 0, size_t max_samples = kMaxSurfaceSamples,
                   const std::string& where = "stock export");

// The surface written as binary STL (through the io area's writer).
void write_stock_stl(const std::string& path, const InProcessStock& stock, double cell = 0);

}  // namespace rosmill::core::stock
