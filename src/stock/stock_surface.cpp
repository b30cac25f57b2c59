#include "rosmill/stock/stock_surface.hpp"

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"

namespace rosmill::core::stock {
namespace {

// Signed distance along z from z to the nearest end of the spans, > 0 in material, clamped to [-h, h], never 0
// (a sample on the surface would give the extraction a degenerate triangle).
float signed_z(const Span* b, const Span* e, double z, double h) {
  double d = -h;
  for (const Span* s = b; s != e; ++s) {
    if (z >= s->lo && z <= s->hi) { d = std::min(z - s->lo, s->hi - z); break; }
    d = std::max(d, -std::min(std::abs(z - s->lo), std::abs(z - s->hi)));
  }
  d = std::clamp(d, -h, h);
  return static_cast<float>(d == 0 ? -1e-6 * h : d);
}

}  // namespace

Mesh stock_surface(const InProcessStock& stock, double cell, size_t max_samples, const std::string& where) {
  const Dexels& m = stock.material();
  const GridSpec& g = m.grid;
  const double c = cell > 0 ? cell : g.cell;
  if (!std::isfinite(c)) throw Error(where, "the cell must be a positive number of mm");
  // Samples at the export cells' centres, one empty sample around; z steps of the cell from below the lowest span.
  const double nx = std::ceil(g.nx * g.cell / c - 1e-9) + 2, ny = std::ceil(g.ny * g.cell / c - 1e-9) + 2;
  const double nz = std::ceil((m.z_max - m.z_min) / c) + 3;
  if (nx * ny * nz > static_cast<double>(max_samples)) {
    const double fit = c * std::cbrt(nx * ny * nz / static_cast<double>(max_samples));
    char what[240];
    std::snprintf(what, sizeof what, "%.3g samples at %g mm (about %.0f MB), more than the %zu allowed: use a cell of "
                  "%.2g mm or more", nx * ny * nz, c, nx * ny * nz * 4 / 1e6, max_samples, fit * 1.01);
    throw Error(where, what);
  }
  const double x0 = g.x0 - 0.5 * c, y0 = g.y0 - 0.5 * c, z0 = m.z_min - 0.5 * c;
  vtkNew<vtkImageData> image;
  image->SetDimensions(static_cast<int>(nx), static_cast<int>(ny), static_cast<int>(nz));
  image->SetOrigin(x0, y0, z0);
  image->SetSpacing(c, c, c);
  vtkNew<vtkFloatArray> field;
  field->SetNumberOfTuples(static_cast<vtkIdType>(nx * ny * nz));
  float* f = field->GetPointer(0);
  const int NX = static_cast<int>(nx), NY = static_cast<int>(ny), NZ = static_cast<int>(nz);
  for (int j = 0; j < NY; ++j)
    for (int i = 0; i < NX; ++i) {
      const double fi = std::floor((x0 + i * c - g.x0) / g.cell), fj = std::floor((y0 + j * c - g.y0) / g.cell);
      const bool inside = i > 0 && j > 0 && i < NX - 1 && j < NY - 1 && fi >= 0 && fj >= 0 && fi < g.nx && fj < g.ny;
      const size_t col = inside ? g.index(static_cast<int>(fi), static_cast<int>(fj)) : 0;
      for (int k = 0; k < NZ; ++k) {
        const size_t at = (static_cast<size_t>(k) * NY + j) * NX + i;
        f[at] = inside ? signed_z(m.begin(col), m.end(col), z0 + k * c, c) : static_cast<float>(-c);
      }
    }
  image->GetPointData()->SetScalars(field);
  vtkNew<vtkFlyingEdges3D> surface;
  surface->SetInputData(image);
  surface->SetValue(0, 0.0);
  surface->ComputeNormalsOff();
  surface->ComputeGradientsOff();
  surface->ComputeScalarsOff();
  surface->Update();
  vtkPolyData* out = surface->GetOutput();
  IndexedTriangles t;
  t.vertices.resize(out->GetNumberOfPoints());
  for (vtkIdType p = 0; p < out->GetNumberOfPoints(); ++p) {
    double xyz[3];
    out->GetPoint(p, xyz);
    t.vertices[p] = Vec3(xyz[0], xyz[1], xyz[2]);
  }
  vtkCellArray* polys = out->GetPolys();
  vtkNew<vtkIdList> ids;
  double volume6 = 0;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) continue;
    const Mesh::Face face{static_cast<uint32_t>(ids->GetId(0)), static_cast<uint32_t>(ids->GetId(1)),
                          static_cast<uint32_t>(ids->GetId(2))};
    volume6 += t.vertices[face[0]].dot(t.vertices[face[1]].cross(t.vertices[face[2]]));
    t.faces.push_back(face);
  }
  // Outward normals (the signed volume positive), whichever way the extraction winds its triangles.
  if (volume6 < 0)
    for (Mesh::Face& face : t.faces) std::swap(face[1], face[2]);
  return mesh_from_indexed(std::move(t));
}

void write_stock_stl(const std::string& path, const InProcessStock& stock, double cell) {
  write_stl(path, stock_surface(stock, cell));
}

}  // namespace rosmill::core::stock
