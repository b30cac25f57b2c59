// A mixed patch cut into parts of equal reachability, recombined among siblings, and described. Everything runs
// on positions inside the patch (SurfacePatches::inner_neighbours), so a patch's work stays in its own slice of
// memory and costs a few passes over its facets.
#include "patch_parts.hpp"

namespace rosmill::core::segment::detail {
namespace {

// The part graph: the lengths the parts share, summed per pair.
void part_graph(const Mesh& mesh, const uint32_t* order, const std::array<uint32_t, 3>* inner, uint32_t base,
                PartsScratch& s) {
  s.graph.clear();
  for (uint32_t c : s.cross) {
    const uint32_t i = c / 4, k = c % 4, j = inner[i][k] - base;
    const uint32_t a = s.part[i], b = s.part[j];
    s.graph.push_back({std::min(a, b), std::max(a, b), edge_length(mesh, mesh.face_edges[order[i]][k])});
  }
  sum_equal_pairs(s.graph);
}

// Merges the small parts into siblings. s.final_part receives each part's final part (numbered by first
// position), s.graph the pairs between final parts. Returns the final count.
uint32_t recombine_parts(uint32_t count, const SizeRule& rule, double total_area, PartsScratch& s) {
  s.final_part.resize(count);
  if (!is_active(rule) || count < 2) {
    for (uint32_t p = 0; p < count; ++p) s.final_part[p] = p;
    return count;
  }
  const std::vector<uint32_t> root = merge_small(s.graph, s.area, s.facets, rule, total_area);
  // Roots are their sets' smallest parts, so numbering the roots in part order numbers by first position.
  uint32_t final_count = 0;
  for (uint32_t p = 0; p < count; ++p) s.final_part[p] = root[p] == p ? final_count++ : s.final_part[root[p]];
  for (LabelPair& q : s.graph) {
    const uint32_t a = s.final_part[q.a], b = s.final_part[q.b];
    q = {std::min(a, b), std::max(a, b), q.length};
  }
  return final_count;
}

// Sizes, normals, reachable areas and neighbours of the final parts, from the parts' sums.
void describe_parts(uint32_t count, uint32_t final_count, PartsScratch& s, PatchParts& out) {
  out.parts.assign(final_count, Patch{});
  out.reachable_area.assign(final_count, 0.0);
  std::vector<Vec3> normal_sum(final_count, Vec3::Zero());
  for (uint32_t p = 0; p < count; ++p) {
    Patch& part = out.parts[s.final_part[p]];
    part.facet_count += s.facets[p];
    part.area += s.area[p];
    normal_sum[s.final_part[p]] += s.normal[p];
    if (s.part_reach[p]) out.reachable_area[s.final_part[p]] += s.area[p];
  }
  for (uint32_t p = 0, offset = 0; p < final_count; ++p) {
    Patch& part = out.parts[p];
    part.id = p;
    part.first_facet = offset;
    offset += part.facet_count;
    part.normal = mean_normal(normal_sum[p], part.area);
  }
  for (const LabelPair& q : s.graph) {
    out.parts[q.a].neighbours.push_back(q.b);
    out.parts[q.b].neighbours.push_back(q.a);
  }
  for (Patch& part : out.parts) std::sort(part.neighbours.begin(), part.neighbours.end());
}

// One pass over the facets (s.part holds final parts): the facets grouped by part, and the half-edges on the
// parts' borders (then grouped by part and chained into loops), and the patch-border edges whose other facets lie
// in other patches.
void trace_borders(const Mesh& mesh, const uint32_t* order, const std::array<uint32_t, 3>* inner, uint32_t base,
                   PartsScratch& s, PatchParts& out) {
  const uint32_t n = uint32_t(s.part.size()), count = uint32_t(out.parts.size());
  s.half.clear();
  out.outer.clear();
  s.fill.resize(count);
  for (uint32_t p = 0; p < count; ++p) s.fill[p] = out.parts[p].first_facet;
  out.order.assign(order, order + n);  // sized by a copy: cheaper than zero-filling, every entry is overwritten
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t f = order[i];
    out.order[s.fill[s.part[i]]++] = f;
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t j = inner[i][k];
      if (j != kNone && s.part[j - base] == s.part[i]) continue;
      const uint32_t from = mesh.faces[f][k], to = mesh.faces[f][(k + 1) % 3];
      if (from == to) continue;  // an edge of a facet with a repeated corner
      bool open = false;
      if (j == kNone) {
        const uint32_t e = mesh.face_edges[f][k];
        open = mesh.edges[e].face_count == 1;
        if (!open) out.outer.push_back({s.part[i], e});
      }
      s.half.push_back({s.part[i], from, to, open});
    }
  }
  s.fill.assign(count + 1, 0);
  for (const HalfEdge& h : s.half) ++s.fill[h.label + 1];
  for (uint32_t p = 0; p < count; ++p) s.fill[p + 1] += s.fill[p];
  s.grouped.resize(s.half.size());
  std::vector<uint32_t> start(s.fill.begin(), s.fill.end());
  for (const HalfEdge& h : s.half) s.grouped[s.fill[h.label]++] = h;
  for (uint32_t p = 0; p < count; ++p)
    chain_loops(s.grouped.data() + start[p], s.grouped.data() + start[p + 1], s.head, s.link, out.parts[p].loops);
  // The outer edges by part (a counting sort), so that the caller meets each part's in one run.
  s.fill.assign(count + 1, 0);
  for (const auto& o : out.outer) ++s.fill[o.first + 1];
  for (uint32_t p = 0; p < count; ++p) s.fill[p + 1] += s.fill[p];
  s.outer.resize(out.outer.size());
  for (const auto& o : out.outer) s.outer[s.fill[o.first]++] = o;
  out.outer.swap(s.outer);
}

}  // namespace

uint32_t flood_patch(const SurfacePatches& patches, const Patch& patch, const std::vector<uint8_t>& reach,
                     PartsScratch& s) {
  const Mesh& mesh = patches.mesh();
  const uint32_t base = patch.first_facet, n = patch.facet_count;
  const uint32_t* order = patches.facet_order().data() + base;
  const std::array<uint32_t, 3>* inner = patches.inner_neighbours().data() + base;
  s.reach.resize(n);
  for (uint32_t i = 0; i < n; ++i) s.reach[i] = reach[order[i]];
  s.part.assign(n, kNone);
  s.cross.clear();
  s.area.clear();
  s.facets.clear();
  s.normal.clear();
  s.part_reach.clear();
  uint32_t count = 0;
  for (uint32_t seed = 0; seed < n; ++seed) {
    if (s.part[seed] != kNone) continue;
    s.part[seed] = count;
    s.stack.assign(1, seed);
    double area = 0.0;
    uint32_t facets = 0;
    Vec3 normal = Vec3::Zero();
    while (!s.stack.empty()) {
      const uint32_t i = s.stack.back();
      s.stack.pop_back();
      const double a = mesh.areas[order[i]];
      area += a;
      ++facets;
      normal += a * mesh.normals[order[i]];
      for (uint32_t k = 0; k < 3; ++k) {
        if (inner[i][k] == kNone) continue;
        const uint32_t j = inner[i][k] - base;
        if (s.reach[j] != s.reach[i]) {
          if (i < j) s.cross.push_back(4 * i + k);
        } else if (s.part[j] == kNone) {
          s.part[j] = count;
          s.stack.push_back(j);
        }
      }
    }
    s.area.push_back(area);
    s.facets.push_back(facets);
    s.normal.push_back(normal);
    s.part_reach.push_back(s.reach[seed]);
    ++count;
  }
  return count;
}

void split_patch(const SurfacePatches& patches, const Patch& patch, const std::vector<uint8_t>& reach,
                 const SizeRule& rule, PartsScratch& s, PatchParts& out) {
  const Mesh& mesh = patches.mesh();
  const uint32_t base = patch.first_facet;
  const uint32_t* order = patches.facet_order().data() + base;
  const std::array<uint32_t, 3>* inner = patches.inner_neighbours().data() + base;
  out.patch = patch.id;
  if (s.head.size() != mesh.vertex_count()) s.head.assign(mesh.vertex_count(), kNone);

  const uint32_t count = flood_patch(patches, patch, reach, s);
  part_graph(mesh, order, inner, base, s);
  const uint32_t final_count = recombine_parts(count, rule, patches.total_area(), s);
  if (final_count < count)
    for (uint32_t& p : s.part) p = s.final_part[p];
  describe_parts(count, final_count, s, out);
  out.small_left = false;
  for (const Patch& part : out.parts)
    out.small_left =
        out.small_left || (final_count > 1 && is_small(rule, part.facet_count, part.area, patches.total_area()));
  trace_borders(mesh, order, inner, base, s, out);
}

}  // namespace rosmill::core::segment::detail
