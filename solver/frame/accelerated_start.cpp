#include "solver/frame/accelerated_start.h"

#include "solver/fracture/debris.h"

namespace galsculpt {

PieceLayout pieceLayout(const SimModel& model, const std::vector<std::uint8_t>& damaged,
                        std::uint64_t revision) {
  const std::vector<std::uint8_t> undamaged(damaged.empty() ? model.numEdges() : 0, 0);
  return pieceLayout(model, censusPieces(model, damaged.empty() ? undamaged : damaged), damaged,
                     revision);
}

PieceLayout pieceLayout(const SimModel& model, const PieceCensus& census,
                        const std::vector<std::uint8_t>& damaged, std::uint64_t revision) {
  const int n = model.numVertices();
  const std::vector<int>& pieceOf = census.pieceOfVertex;
  PieceLayout out;
  out.pieceStart.assign(census.pieces + 1, 0);
  for (int v = 0; v < n; ++v) ++out.pieceStart[pieceOf[v] + 1];
  for (int p = 0; p < census.pieces; ++p) out.pieceStart[p + 1] += out.pieceStart[p];
  out.pieceVertices.resize(n);
  std::vector<int> next(out.pieceStart.begin(), out.pieceStart.end() - 1);
  for (int v = 0; v < n; ++v) out.pieceVertices[next[pieceOf[v]]++] = v;
  out.revision = revision;
  out.pieceOf = pieceOf;
  // Elements between pieces, in element order (the same on every executor), and each piece's
  // corners in them.
  for (int t = 0; t < model.numTets(); ++t)
    if (!census.isWhole[t]) out.sharedTets.push_back(t);
  out.couplingStart.assign(census.pieces + 1, 0);
  for (int t : out.sharedTets)
    for (int a = 0; a < 4; ++a) ++out.couplingStart[pieceOf[model.mesh.tets[t][a]] + 1];
  for (int p = 0; p < census.pieces; ++p) out.couplingStart[p + 1] += out.couplingStart[p];
  out.couplingSlot.resize(out.couplingStart.back());
  std::vector<int> at(out.couplingStart.begin(), out.couplingStart.end() - 1);
  for (size_t i = 0; i < out.sharedTets.size(); ++i)
    for (int a = 0; a < 4; ++a)
      out.couplingSlot[at[pieceOf[model.mesh.tets[out.sharedTets[i]][a]]]++] =
          static_cast<int>(12 * i + 3 * a);
  // Damaged edges between pieces, under each of their two pieces (in edge order).
  const auto across = [&](int e) {
    return !damaged.empty() && damaged[e] &&
           pieceOf[model.edges[e][0]] != pieceOf[model.edges[e][1]];
  };
  out.crackStart.assign(census.pieces + 1, 0);
  for (int e = 0; e < model.numEdges(); ++e) {
    if (!across(e)) continue;
    ++out.crackStart[pieceOf[model.edges[e][0]] + 1];
    ++out.crackStart[pieceOf[model.edges[e][1]] + 1];
  }
  for (int p = 0; p < census.pieces; ++p) out.crackStart[p + 1] += out.crackStart[p];
  out.crackEnds.resize(2 * out.crackStart.back());
  out.crackRestLengthSq.resize(out.crackStart.back());
  std::vector<int> slot(out.crackStart.begin(), out.crackStart.end() - 1);
  for (int e = 0; e < model.numEdges(); ++e) {
    if (!across(e)) continue;
    const int a = model.edges[e][0], b = model.edges[e][1];
    const double restSq = (model.mesh.vertices[b] - model.mesh.vertices[a]).squaredNorm();
    for (const auto& [own, other] : {std::pair{a, b}, std::pair{b, a}}) {
      const int i = slot[pieceOf[own]]++;
      out.crackEnds[2 * i] = own;
      out.crackEnds[2 * i + 1] = other;
      out.crackRestLengthSq[i] = restSq;
    }
  }
  return out;
}

}  // namespace galsculpt
