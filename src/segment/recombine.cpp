// The recombination step of Lefebvre & Lauwers, "STL Model Segmentation for Multi-Axis Machining Operations Planning":
// patches too small to be machined on their own join the neighbour they
// share the longest boundary with. Works on labels, so phase 1 patches and phase 2 segments share it.
#include <algorithm>

#include "labelling.hpp"
#include "union_find.hpp"

namespace rosmill::core::segment::detail {

// Pairs come one per border edge (tens of thousands): they are summed in an open-addressing table sized to them.
void sum_equal_pairs(std::vector<LabelPair>& pairs) {
  size_t capacity = 64;
  while (capacity < 2 * pairs.size()) capacity <<= 1;
  // Index into the reduced prefix of `pairs`. The table is kept per thread: recombination calls this once per
  // round, patch after patch on both cores, and allocations there contend for one heap.
  thread_local std::vector<uint32_t> slot;
  slot.assign(capacity, kNone);
  const size_t mask = capacity - 1;
  size_t out = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const LabelPair p = pairs[i];
    const uint64_t key = uint64_t(p.a) << 32 | p.b;
    for (size_t h = (key * 0x9E3779B97F4A7C15ull) >> 40 & mask;; h = (h + 1) & mask) {
      if (slot[h] == kNone) {
        slot[h] = uint32_t(out);
        pairs[out++] = p;
        break;
      }
      LabelPair& q = pairs[slot[h]];
      if (q.a == p.a && q.b == p.b) {
        q.length += p.length;
        break;
      }
    }
  }
  pairs.resize(out);
}

bool is_active(const SizeRule& rule) {
  return rule.kind == SizeRule::Kind::FacetCount ? rule.min_facets > 0 : rule.min_area_fraction > 0;
}

bool is_small(const SizeRule& rule, size_t facets, double area, double total_area) {
  if (rule.kind == SizeRule::Kind::FacetCount) return facets < rule.min_facets;
  return area < rule.min_area_fraction * total_area;
}

uint32_t compact_labels(std::vector<uint32_t>& labels, uint32_t label_bound) {
  std::vector<uint32_t> map(label_bound, kNone);
  uint32_t count = 0;
  for (uint32_t& l : labels) {
    if (map[l] == kNone) map[l] = count++;
    l = map[l];
  }
  return count;
}

std::vector<LabelPair> label_pairs(const Mesh& mesh, const std::vector<uint32_t>& labels,
                                   const std::vector<uint32_t>& edges) {
  std::vector<LabelPair> pairs;
  pairs.reserve(edges.size());  // one pair per manifold edge between two labels
  for (uint32_t e : edges) {
    const MeshEdge& edge = mesh.edges[e];
    if (edge.face_count < 2) continue;
    const uint32_t* faces = mesh.edge_faces.data() + edge.first_face;
    double length = -1.0;
    for (uint32_t i = 0; i < edge.face_count; ++i)
      for (uint32_t j = i + 1; j < edge.face_count; ++j) {
        const uint32_t a = labels[faces[i]], b = labels[faces[j]];
        if (a == b) continue;
        if (length < 0.0) length = edge_length(mesh, e);
        pairs.push_back({std::min(a, b), std::max(a, b), length});
      }
  }
  sum_equal_pairs(pairs);
  return pairs;
}

std::vector<uint32_t> merge_small(std::vector<LabelPair>& graph, std::vector<double> area,
                                  std::vector<uint32_t> facets, const SizeRule& rule, double total_area,
                                  const std::vector<uint32_t>* group) {
  const uint32_t count = uint32_t(area.size());
  std::vector<uint32_t> root_group;
  if (group) root_group = *group;
  // The small roots, ascending (merges keep them so: a root only grows, and a merged set's root is its smallest
  // label), and a flag per label: a round only visits these. The label graph is rewritten after each round in
  // terms of the merged roots, so it shrinks round by round. The choice of each small label's neighbour does not
  // depend on the order of the pairs.
  std::vector<uint32_t> small;
  std::vector<uint8_t> is_small_root(count, 0);
  for (uint32_t l = 0; l < count; ++l)
    if (is_small(rule, facets[l], area[l], total_area)) {
      small.push_back(l);
      is_small_root[l] = 1;
    }
  UnionFind sets(count);
  std::vector<LabelPair> pairs;
  pairs.reserve(graph.size());
  struct Choice {
    uint32_t to = kNone;
    bool same = false;
    double length = 0.0;
  };
  std::vector<Choice> best(count);
  while (!small.empty()) {
    // Dominant neighbour of each small root: same group first, then the longest shared boundary, then the
    // larger neighbour, then the lower id.
    auto offer = [&](uint32_t from, uint32_t to, double length) {
      if (!is_small_root[from]) return;
      Choice& c = best[from];
      const bool same = group && root_group[from] == root_group[to];
      bool better = c.to == kNone;
      if (!better && same != c.same) better = same;
      else if (!better && length != c.length) better = length > c.length;
      else if (!better && area[to] != area[c.to]) better = area[to] > area[c.to];
      else if (!better) better = to < c.to;
      if (better) c = {to, same, length};
    };
    for (const LabelPair& p : graph) {
      offer(p.a, p.b, p.length);
      offer(p.b, p.a, p.length);
    }
    bool merged = false;
    for (uint32_t r : small) {
      const uint32_t to = best[r].to;
      if (to == kNone) continue;
      best[r].to = kNone;
      const uint32_t target_group = group ? root_group[sets.find(to)] : 0;
      const uint32_t a = sets.find(r), b = sets.find(to);
      if (a == b) continue;
      const uint32_t root = sets.unite(a, b);
      const uint32_t other = root == a ? b : a;
      area[root] += area[other];
      facets[root] += facets[other];
      if (group) root_group[root] = target_group;
      merged = true;
    }
    if (!merged) break;
    // The label graph as it stands after this round's merges.
    pairs.clear();
    for (const LabelPair& p : graph) {
      const uint32_t a = sets.find(p.a), b = sets.find(p.b);
      if (a != b) pairs.push_back({std::min(a, b), std::max(a, b), p.length});
    }
    sum_equal_pairs(pairs);
    graph.swap(pairs);
    size_t kept = 0;
    for (uint32_t r : small) {
      is_small_root[r] = sets.find(r) == r && is_small(rule, facets[r], area[r], total_area);
      if (is_small_root[r]) small[kept++] = r;
    }
    small.resize(kept);
  }
  std::vector<uint32_t> root(count);
  for (uint32_t l = 0; l < count; ++l) root[l] = sets.find(l);
  return root;
}

uint32_t recombine(const Mesh& mesh, std::vector<uint32_t>& labels, uint32_t count,
                   const std::vector<uint32_t>& edges, const SizeRule& rule, double total_area,
                   std::vector<LabelPair>& pairs_out, const std::vector<uint32_t>* group) {
  pairs_out = label_pairs(mesh, labels, edges);
  if (!is_active(rule) || count < 2) return count;
  std::vector<double> area(count, 0.0);
  std::vector<uint32_t> facets(count, 0);
  for (size_t f = 0; f < labels.size(); ++f) {
    area[labels[f]] += mesh.areas[f];
    ++facets[labels[f]];
  }
  const std::vector<uint32_t> root =
      merge_small(pairs_out, std::move(area), std::move(facets), rule, total_area, group);
  // Final labels numbered in the order of their first facet, as compact_labels() numbers them; the last
  // round's graph (in final roots, summed) becomes the pairs of the final labels.
  std::vector<uint32_t> final_label(count, kNone);
  uint32_t final_count = 0;
  for (uint32_t& l : labels) {
    uint32_t& mapped = final_label[root[l]];
    if (mapped == kNone) mapped = final_count++;
    l = mapped;
  }
  for (LabelPair& p : pairs_out) {
    const uint32_t a = final_label[p.a], b = final_label[p.b];
    p = {std::min(a, b), std::max(a, b), p.length};
  }
  return final_count;
}

}  // namespace rosmill::core::segment::detail
