// Figures and the .dat export of a slicing.
#include <cstdio>
#include <memory>

#include "rosmill/error.hpp"
#include "rosmill/slice/slicer.hpp"

namespace rosmill::core {

double signed_area(const std::vector<Vec2>& p) {
  double twice = 0.0;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) twice += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return 0.5 * twice;
}

SliceSummary summarize(const std::vector<SliceLayer>& layers) {
  SliceSummary s;
  s.layers = layers.size();
  for (const SliceLayer& l : layers)
    for (const Contour& c : l.contours) {
      ++s.contours;
      s.open_contours += c.closed ? 0 : 1;
      s.points += c.points.size();
    }
  return s;
}

void write_slices_dat(const std::string& path, const std::vector<SliceLayer>& layers) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw Error(path, "cannot open for writing");
  bool first = true;
  for (const SliceLayer& l : layers)
    for (const Contour& c : l.contours) {
      if (!first) std::fputc('\n', f.get());
      first = false;
      for (const Vec2& p : c.points) std::fprintf(f.get(), "%.6f %.6f %.6f\n", p.x(), p.y(), l.z);
      if (c.closed) std::fprintf(f.get(), "%.6f %.6f %.6f\n", c.points[0].x(), c.points[0].y(), l.z);
    }
  if (std::ferror(f.get())) throw Error(path, "write failed");
}

}  // namespace rosmill::core
