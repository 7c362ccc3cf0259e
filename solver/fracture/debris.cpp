#include "solver/fracture/debris.h"

#include <algorithm>

#include "solver/mesh/union_find.h"

namespace galsculpt {

PieceCensus censusPieces(const SimModel& model, const std::vector<std::uint8_t>& damaged) {
  const int n = model.numVertices();
  UnionFind uf(n);
  for (int e = 0; e < model.numEdges(); ++e) {
    if (!damaged[e]) uf.unite(model.edges[e][0], model.edges[e][1]);
  }
  PieceCensus c;
  std::vector<int> number(n, -1);
  c.pieceOfVertex.resize(n);
  for (int v = 0; v < n; ++v) {
    int& p = number[uf.find(v)];
    if (p < 0) p = c.pieces++;
    c.pieceOfVertex[v] = p;
  }
  c.restVolume.assign(c.pieces, 0.0);
  c.vertexCount.assign(c.pieces, 0);
  c.wholeTets.assign(c.pieces, 0);
  c.wholeVolume.assign(c.pieces, 0.0);
  c.isWhole.assign(model.numTets(), 0);
  for (int v = 0; v < n; ++v) ++c.vertexCount[c.pieceOfVertex[v]];
  for (int t = 0; t < model.numTets(); ++t) {
    const double volume = model.rest[t].volume;
    c.bodyRestVolume += volume;
    const Tet& tet = model.mesh.tets[t];
    for (int a = 0; a < 4; ++a) c.restVolume[c.pieceOfVertex[tet[a]]] += 0.25 * volume;
    const int p = c.pieceOfVertex[tet[0]];
    if (c.pieceOfVertex[tet[1]] != p || c.pieceOfVertex[tet[2]] != p ||
        c.pieceOfVertex[tet[3]] != p)
      continue;
    c.isWhole[t] = 1;
    ++c.wholeTets[p];
    c.wholeVolume[p] += volume;
    c.wholeRestVolume += volume;
  }
  return c;
}

std::vector<std::uint8_t> debrisPieces(const PieceCensus& census, double fraction) {
  std::vector<std::uint8_t> debris(census.pieces, 0);
  const double below = fraction * census.bodyRestVolume;
  if (!(fraction > 0.0)) return debris;
  for (int p = 0; p < census.pieces; ++p)
    debris[p] = census.wholeTets[p] == 0 || census.wholeVolume[p] < below;
  return debris;
}

std::vector<std::uint8_t> debrisVertices(const PieceCensus& census, double fraction) {
  const std::vector<std::uint8_t> debris = debrisPieces(census, fraction);
  if (std::none_of(debris.begin(), debris.end(), [](std::uint8_t d) { return d != 0; })) return {};
  std::vector<std::uint8_t> out(census.pieceOfVertex.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = debris[census.pieceOfVertex[v]];
  return out;
}

}  // namespace galsculpt
