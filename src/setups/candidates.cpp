#include "rosmill/setups/candidates.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rosmill/geometry/setup_frame.hpp"

namespace rosmill::core::setups {
namespace {

struct Proposal {
  Vec3 direction;
  double area;
  std::string source;
};

// A flat face: a patch whose every facet lies within the tolerance of its normal.
bool flat(const segment::SurfacePatches& sp, const segment::Patch& p, double cos_tolerance) {
  if (p.normal.isZero()) return false;
  const Mesh& mesh = sp.mesh();
  for (const uint32_t* f = sp.facets_begin(p); f != sp.facets_end(p); ++f)
    if (mesh.areas[*f] > 0 && mesh.normals[*f].dot(p.normal) < cos_tolerance) return false;
  return true;
}

std::string share_text(const char* what, double area, double total) {
  char s[96];
  std::snprintf(s, sizeof s, "%s (%.4g mm^2, %.1f%% of the area)", what, area, 100.0 * area / total);
  return s;
}

}  // namespace

std::vector<Candidate> candidate_directions(const segment::EgiSet& egis, const CandidateOptions& o) {
  std::vector<Candidate> out;
  for (const char* name : {"+Z", "-Z", "+X", "-X", "+Y", "-Y"}) {
    const SetupFrame s = named_setup(name);
    out.push_back({s.tool_axis, s.name, "axis"});
  }
  const segment::SurfacePatches& sp = egis.patches();
  const double total = sp.total_area();
  if (!(total > 0)) return out;
  std::vector<Proposal> flats, peaks;
  const double cos_flat = std::cos(o.flat_tolerance_deg * M_PI / 180.0);
  for (const segment::Patch& p : sp.patches())
    if (p.area >= o.min_share * total && flat(sp, p, cos_flat))
      flats.push_back({p.normal, p.area, share_text(("flat face, patch " + std::to_string(p.id)).c_str(), p.area, total)});
  // The whole part's EGI: its patches' summed per bin.
  const segment::EgiBins& bins = egis.bins();
  std::vector<double> egi(bins.size(), 0.0);
  for (size_t p = 0; p < sp.count(); ++p) {
    const segment::PatchEgi& e = egis.egi(p);
    for (size_t k = 0; k < e.bins.size(); ++k) egi[e.bins[k]] += e.areas[k];
  }
  for (uint32_t b = 0; b < bins.size(); ++b)
    if (egi[b] >= o.min_share * total) peaks.push_back({bins.centre(b), egi[b], share_text("EGI peak", egi[b], total)});
  const auto larger = [](const Proposal& a, const Proposal& b) { return a.area > b.area; };
  std::stable_sort(flats.begin(), flats.end(), larger);
  std::stable_sort(peaks.begin(), peaks.end(), larger);
  // Flat faces first (their normals are exact), then the EGI's peaks, each kept when far enough from those taken.
  const double cos_sep = std::cos(o.min_separation_deg * M_PI / 180.0);
  size_t extra = 0;
  for (const std::vector<Proposal>* list : {&flats, &peaks})
    for (const Proposal& p : *list) {
      if (extra >= o.max_extra) break;
      const Vec3 d = p.direction.normalized();
      if (std::any_of(out.begin(), out.end(), [&](const Candidate& c) { return c.direction.dot(d) > cos_sep; }))
        continue;
      out.push_back({d, setup_name_of(d), p.source});
      ++extra;
    }
  return out;
}

}  // namespace rosmill::core::setups
