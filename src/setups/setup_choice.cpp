#include "rosmill/setups/setup_choice.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "rosmill/error.hpp"
#include "rosmill/geometry/placement.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/segment/egi.hpp"
#include "rosmill/seconds_since.hpp"

namespace rosmill::core::setups {
namespace {

using Clock = std::chrono::steady_clock;

// The samples on the face the part is held by: facing the held direction (within a degree) and on the part's
// extreme plane that way.
std::vector<uint8_t> held_samples(const Mesh& part, const SurfaceSamples& s, const std::optional<Vec3>& held) {
  std::vector<uint8_t> out(s.size(), 0);
  if (!held) return out;
  const Vec3 d = held->normalized();
  double extreme = -INFINITY;
  for (const Vec3& v : part.vertices) extreme = std::max(extreme, v.dot(d));
  const double tolerance = 1e-6 * (1.0 + part.bbox.size().norm());
  for (size_t k = 0; k < s.size(); ++k)
    out[k] = s.normals[k].dot(d) > std::cos(M_PI / 180.0) && s.points[k].dot(d) > extreme - tolerance;
  return out;
}

// The units the search counts: a face that some candidate reaches whole, with the set of those candidates, or one
// sample of a face no candidate reaches whole, with the set of candidates that reach it; merged by set.
struct Units {
  std::vector<uint64_t> sets;
  std::vector<double> areas;
  double total = 0;  // of the units some candidate covers
};

struct PatchReach {
  double area = 0;                 // its samples' area, the held ones left out
  std::vector<double> reached;     // per candidate
  uint64_t whole = 0;              // the candidates reaching it whole
};

std::vector<PatchReach> patch_reach(const std::vector<uint64_t>& reached, const SurfaceSamples& s,
                                    const std::vector<uint32_t>& patch_of, const std::vector<uint8_t>& held,
                                    size_t patches, size_t candidates, double whole_share) {
  std::vector<PatchReach> out(patches);
  for (PatchReach& p : out) p.reached.assign(candidates, 0.0);
  for (size_t k = 0; k < s.size(); ++k) {
    if (held[k]) continue;
    PatchReach& p = out[patch_of[k]];
    p.area += s.weights[k];
    for (size_t c = 0; c < candidates; ++c)
      if (reached[k] >> c & 1) p.reached[c] += s.weights[k];
  }
  for (PatchReach& p : out)
    for (size_t c = 0; c < candidates; ++c)
      if (p.area > 0 && p.reached[c] >= whole_share * p.area) p.whole |= uint64_t(1) << c;
  return out;
}

Units units_of(const std::vector<uint64_t>& reached, const SurfaceSamples& s, const std::vector<uint32_t>& patch_of,
               const std::vector<uint8_t>& held, const std::vector<PatchReach>& patches) {
  std::map<uint64_t, double> by_set;
  for (const PatchReach& p : patches)
    if (p.whole) by_set[p.whole] += p.area;
  for (size_t k = 0; k < s.size(); ++k)
    if (!held[k] && !patches[patch_of[k]].whole && reached[k]) by_set[reached[k]] += s.weights[k];
  Units u;
  for (const auto& [set, area] : by_set) {
    u.sets.push_back(set);
    u.areas.push_back(area);
    u.total += area;
  }
  return u;
}

double cover(const Units& u, uint64_t set) {
  double a = 0;
  for (size_t k = 0; k < u.sets.size(); ++k)
    if (u.sets[k] & set) a += u.areas[k];
  return a;
}

// The next larger set with the same number of members (Gosper's hack).
uint64_t next_same_size(uint64_t v) {
  const uint64_t t = v | (v - 1);
  return (t + 1) | (((~t & -~t) - 1) >> (__builtin_ctzll(v) + 1));
}

struct Search {
  uint64_t chosen = 0;
  uint64_t compared = 0;
  bool exhaustive = true;
};

// The fewest members of `usable` whose cover is within `slack` of what they all cover; the largest cover among
// those, the first in candidate order on a tie. Every set of each size is compared, smallest sizes first.
Search exhaustive_search(const Units& u, uint64_t usable, double slack) {
  Search s;
  std::vector<int> members;
  for (int c = 0; c < 64; ++c)
    if (usable >> c & 1) members.push_back(c);
  const int m = static_cast<int>(members.size());
  const double target = cover(u, usable) - slack;
  for (int k = 1; k <= m; ++k) {
    double best = -1;
    uint64_t best_set = 0;
    // Gosper's enumeration of the k-member subsets of the m usable candidates, as bits over them.
    for (uint64_t pick = (uint64_t(1) << k) - 1; pick < (uint64_t(1) << m); pick = next_same_size(pick)) {
      uint64_t set = 0;
      for (int i = 0; i < m; ++i)
        if (pick >> i & 1) set |= uint64_t(1) << members[i];
      ++s.compared;
      const double a = cover(u, set);
      if (a > best + 1e-9 * (1 + u.total)) best = a, best_set = set;
    }
    if (best >= target) {
      s.chosen = best_set;
      return s;
    }
  }
  s.chosen = usable;
  return s;
}

// Beyond the exhaustive limit: the candidate adding the most cover, until what is left is within the slack.
Search greedy_search(const Units& u, uint64_t usable, double slack) {
  Search s;
  s.exhaustive = false;
  const double target = cover(u, usable) - slack;
  while (cover(u, s.chosen) < target) {
    uint64_t best = 0;
    double best_area = -1;
    for (int c = 0; c < 64; ++c) {
      const uint64_t bit = uint64_t(1) << c;
      if (!(usable & bit) || (s.chosen & bit)) continue;
      ++s.compared;
      const double a = cover(u, s.chosen | bit);
      if (a > best_area) best_area = a, best = bit;
    }
    if (!best) break;
    s.chosen |= best;
  }
  return s;
}

}  // namespace

std::vector<int> facet_setups(const SetupChoice& c, size_t facets) {
  const size_t n = c.setups.size() + 1;  // the last column: no setup
  std::vector<double> area(facets * n, 0.0);
  for (size_t k = 0; k < c.samples.size(); ++k) {
    const int by = c.machined_by[k];
    area[c.samples.facets[k] * n + (by < 0 ? n - 1 : size_t(by))] += c.samples.weights[k];
  }
  std::vector<int> out(facets, -1);
  for (size_t f = 0; f < facets; ++f) {
    const double* a = area.data() + f * n;
    const size_t best = std::max_element(a, a + n) - a;
    out[f] = best + 1 == n || a[best] == 0 ? -1 : static_cast<int>(best);
  }
  return out;
}

SetupChoice choose_setups(const Mesh& part, const segment::SurfacePatches& patches, const ChoiceOptions& o) {
  check_has_area(part, "setups: the part");
  check_tool(o.tool, "setups: tool");
  if (!(o.min_gain_share >= 0 && o.min_gain_share < 1)) throw Error("setups", "the least gain must lie in [0, 1)");
  if (!(o.whole_share > 0 && o.whole_share <= 1)) throw Error("setups", "the whole share must lie in (0, 1]");
  const auto t0 = Clock::now();
  SetupChoice r;
  r.samples = sample_surface(part, o.spacing > 0 ? o.spacing : sample_spacing(part));
  const SurfaceSamples& s = r.samples;
  const std::vector<uint8_t> held = held_samples(part, s, o.held_face);
  std::vector<uint32_t> patch_of(s.size());
  for (size_t k = 0; k < s.size(); ++k) patch_of[k] = patches.label(s.facets[k]);

  if (o.directions.empty()) {
    r.candidates = candidate_directions(segment::EgiSet(patches), o.candidates);
  } else {
    for (const Vec3& d : o.directions) {
      const SetupFrame f = direction_setup(d, "setups: direction");
      r.candidates.push_back({f.tool_axis, f.name, "given"});
    }
  }
  if (r.candidates.size() > 64) throw Error("setups", "at most 64 candidate directions");
  const size_t n = r.candidates.size();
  r.candidate_area.assign(n, 0.0);
  r.candidate_refused.assign(n, "");
  r.candidate_unfit.assign(n, 0);
  const ReachTool tool = reach_tool(o.tool);
  const Box3 stock = o.stock.empty() ? part.bbox : o.stock;
  std::vector<uint64_t> reached(s.size(), 0), fixture_blocked(s.size(), 0);
  std::vector<uint8_t> reached_unfit(s.size(), 0);  // reached by a candidate that does not fit the machine
  uint64_t usable = 0;
  for (size_t c = 0; c < n; ++c) {
    const Candidate& cand = r.candidates[c];
    if (o.held_face && cand.direction.dot(o.held_face->normalized()) > std::cos(M_PI / 180.0)) {
      r.candidate_refused[c] = "the part is held by the face it points at";
      continue;
    }
    const SetupFrame setup = direction_setup(cand.direction);
    // A direction the machine cannot take or room it lacks: not a setup; what it alone would reach is reported as
    // left for want of a machine that does.
    const auto unfit = [&](const std::string& why, const std::vector<Vec3>& fixture) {
      r.candidate_refused[c] = why;
      r.candidate_unfit[c] = 1;
      const std::vector<Reach> reach = reach_along(part, s, setup, tool, fixture, o.max_angle_deg);
      for (size_t k = 0; k < s.size(); ++k) reached_unfit[k] |= !held[k] && reach[k] == Reach::Reached;
    };
    if (const std::string why = o.direction_refused ? o.direction_refused(cand.direction) : ""; !why.empty()) {
      unfit(why, {});
      continue;
    }
    const Box3 turned = placed(stock, setup.placement);
    fixture::Fixture holding;
    try {
      holding = fixture::place_fixture(o.fixture.value_or(fixture::FixtureSpec{}), turned,
                                    "setup " + cand.name + " fixture");
    } catch (const Error& e) {
      r.candidate_refused[c] = e.what();
      continue;
    }
    const std::vector<Vec3> fixture = o.fixture ? fixture::fixture_corners(holding) : std::vector<Vec3>{};
    const std::string misfit = o.machine ? machine_misfit(*o.machine, turned, holding) : "";
    if (!misfit.empty()) {
      unfit(misfit, fixture);
      continue;
    }
    usable |= uint64_t(1) << c;
    const std::vector<Reach> reach = reach_along(part, s, setup, tool, fixture, o.max_angle_deg);
    for (size_t k = 0; k < s.size(); ++k) {
      if (held[k]) continue;
      if (reach[k] == Reach::Reached) {
        reached[k] |= uint64_t(1) << c;
        r.candidate_area[c] += s.weights[k];
      } else if (reach[k] == Reach::Fixture) {
        fixture_blocked[k] |= uint64_t(1) << c;
      }
    }
  }
  r.reach_seconds = seconds_since(t0);

  const auto t1 = Clock::now();
  const std::vector<PatchReach> by_patch =
      patch_reach(reached, s, patch_of, held, patches.count(), n, o.whole_share);
  const Units units = units_of(reached, s, patch_of, held, by_patch);
  for (size_t k = 0; k < s.size(); ++k) r.total_area += s.weights[k];
  const double slack = o.min_gain_share * r.total_area;
  const bool exhaustive = static_cast<size_t>(__builtin_popcountll(usable)) <= o.exhaustive_limit;
  Search found;
  if (!o.search) found.chosen = usable;
  else found = exhaustive ? exhaustive_search(units, usable, slack) : greedy_search(units, usable, slack);
  r.exhaustive = found.exhaustive;
  r.subsets = found.compared;
  r.best_cover = cover(units, usable);
  r.search_seconds = seconds_since(t1);
  r.reached = reached;

  // The chosen setups, in candidate order, and who machines each sample.
  std::vector<size_t> chosen;
  for (size_t c = 0; c < n; ++c)
    if (found.chosen >> c & 1) chosen.push_back(c);
  r.machined_by.assign(s.size(), -1);
  for (size_t k = 0; k < s.size(); ++k) {
    if (held[k]) continue;
    const PatchReach& p = by_patch[patch_of[k]];
    // A face reached whole by a chosen setup goes to the one most nearly head-on; else each sample does.
    const uint64_t whole = p.whole & found.chosen;
    const Vec3 facing = whole ? patches.patch(patch_of[k]).normal : s.normals[k];
    double best = -INFINITY;
    for (size_t i = 0; i < chosen.size(); ++i) {
      const uint64_t bit = uint64_t(1) << chosen[i];
      if (!(reached[k] & bit) || (whole && !(whole & bit))) continue;
      const double a = facing.dot(r.candidates[chosen[i]].direction);
      if (a > best) best = a, r.machined_by[k] = static_cast<int>(i);
    }
    // The few samples of a whole face that its setup does not reach go to another that does.
    if (r.machined_by[k] < 0 && whole)
      for (size_t i = 0; i < chosen.size(); ++i)
        if (reached[k] >> chosen[i] & 1) r.machined_by[k] = static_cast<int>(i);
  }
  for (size_t i = 0; i < chosen.size(); ++i) {
    const Candidate& c = r.candidates[chosen[i]];
    ChosenSetup cs;
    cs.candidate = chosen[i];
    cs.direction = c.direction;
    cs.name = c.name;
    cs.source = c.source;
    cs.reachable_area = r.candidate_area[chosen[i]];
    std::map<uint32_t, double> by;
    for (size_t k = 0; k < s.size(); ++k)
      if (r.machined_by[k] == static_cast<int>(i)) by[patch_of[k]] += s.weights[k];
    for (const auto& [patch, area] : by) {
      cs.segments.push_back({patch, area, patches.patch(patch).normal});
      cs.assigned_area += area;
    }
    r.machined_area += cs.assigned_area;
    r.setups.push_back(std::move(cs));
  }
  // What no chosen setup machines, by patch and reason.
  std::map<std::pair<uint32_t, std::string>, Unreached> places;
  r.unmachined.assign(s.size(), Unmachined::No);
  for (size_t k = 0; k < s.size(); ++k) {
    if (r.machined_by[k] >= 0) continue;
    r.unmachined[k] = held[k]                              ? Unmachined::Held
                      : (fixture_blocked[k] & found.chosen) ? Unmachined::Fixture
                      : reached[k]                         ? Unmachined::NotChosen
                      : reached_unfit[k]                   ? Unmachined::Machine
                                                           : Unmachined::Unreachable;
    static const char* const kReason[] = {"", "held", "fixture", "not chosen", "unreachable", "machine"};
    const std::string reason = kReason[static_cast<int>(r.unmachined[k])];
    Unreached& u = places[{patch_of[k], reason}];
    u.patch = patch_of[k];
    u.reason = reason;
    u.area += s.weights[k];
    u.centroid += s.weights[k] * s.points[k];
    u.normal = patches.patch(patch_of[k]).normal;
    r.unreachable_area += s.weights[k];
  }
  for (auto& [key, u] : places) {
    u.centroid /= u.area;
    r.unreachable.push_back(u);
  }
  std::stable_sort(r.unreachable.begin(), r.unreachable.end(),
                   [](const Unreached& a, const Unreached& b) { return a.area > b.area; });
  return r;
}

}  // namespace rosmill::core::setups
