#include "solver/fracture/cracked_sections.h"

#include <algorithm>

#include "solver/mesh/union_find.h"

namespace galsculpt {

std::vector<int> crackedSectionEdges(const SimModel& model,
                                     const std::vector<std::array<int, 4>>& neighbours,
                                     const std::vector<std::uint8_t>& damaged, double fraction) {
  const int tets = model.numTets(), verts = model.numVertices();
  if (!(fraction > 0.0) || tets == 0) return {};
  // Undamaged elements, joined through their shared faces.
  std::vector<std::uint8_t> sound(tets, 1);
  double body = 0.0;
  for (int t = 0; t < tets; ++t) {
    body += model.rest[t].volume;
    for (const int e : model.tetEdges[t])
      if (damaged[e]) sound[t] = 0;
  }
  UnionFind joined(tets);
  for (int t = 0; t < tets; ++t) {
    if (!sound[t]) continue;
    for (const int n : neighbours[t])
      if (n > t && sound[n]) joined.unite(t, n);
  }
  std::vector<double> volume(tets, 0.0);
  for (int t = 0; t < tets; ++t)
    if (sound[t]) volume[joined.find(t)] += model.rest[t].volume;
  // The parts, numbered in first-tet order.
  std::vector<int> part(tets, -1);
  std::vector<double> partVolume;
  for (int t = 0; t < tets; ++t) {
    const int root = joined.find(t);
    if (!sound[t] || volume[root] < fraction * body || part[root] >= 0) continue;
    part[root] = static_cast<int>(partVolume.size());
    partVolume.push_back(volume[root]);
  }
  if (partVolume.size() < 2) return {};
  // Each vertex of a part's element: that part (the larger where it touches two).
  std::vector<int> label(verts, -1);
  for (int t = 0; t < tets; ++t) {
    if (!sound[t]) continue;
    const int p = part[joined.find(t)];
    if (p < 0) continue;
    for (const int v : model.mesh.tets[t]) {
      const int q = label[v];
      if (q < 0 || partVolume[p] > partVolume[q] || (partVolume[p] == partVolume[q] && p < q))
        label[v] = p;
    }
  }
  // The others: the part nearest through intact edges.
  std::vector<int> start(verts + 1, 0), next;
  for (int e = 0; e < model.numEdges(); ++e) {
    if (damaged[e]) continue;
    ++start[model.edges[e][0] + 1];
    ++start[model.edges[e][1] + 1];
  }
  for (int v = 0; v < verts; ++v) start[v + 1] += start[v];
  std::vector<int> fill(start.begin(), start.end() - 1);
  next.resize(start[verts]);
  for (int e = 0; e < model.numEdges(); ++e) {
    if (damaged[e]) continue;
    const int a = model.edges[e][0], b = model.edges[e][1];
    next[fill[a]++] = b;
    next[fill[b]++] = a;
  }
  std::vector<int> queue;
  queue.reserve(verts);
  for (int v = 0; v < verts; ++v)
    if (label[v] >= 0) queue.push_back(v);
  for (size_t head = 0; head < queue.size(); ++head) {
    const int v = queue[head];
    for (int i = start[v]; i < start[v + 1]; ++i) {
      const int w = next[i];
      if (label[w] >= 0) continue;
      label[w] = label[v];
      queue.push_back(w);
    }
  }
  std::vector<int> out;
  for (int e = 0; e < model.numEdges(); ++e) {
    if (damaged[e]) continue;
    const int a = label[model.edges[e][0]], b = label[model.edges[e][1]];
    if (a >= 0 && b >= 0 && a != b) out.push_back(e);
  }
  return out;
}

}  // namespace galsculpt
