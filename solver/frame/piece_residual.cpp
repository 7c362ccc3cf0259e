#include "solver/frame/piece_residual.h"

#include <algorithm>

namespace galsculpt {

PieceResidualLayout pieceResidualLayout(const PieceLayout& pieces, int chunk) {
  PieceResidualLayout layout;
  for (int p = 0; p < pieces.pieces(); ++p) {
    const int begin = pieces.pieceStart[p], end = pieces.pieceStart[p + 1];
    if (end - begin <= kMeasuredPieceVertices) continue;
    for (int i = begin; i < end; i += chunk) {
      const auto from = pieces.pieceVertices.begin();
      layout.vertices.insert(layout.vertices.end(), from + i, from + std::min(i + chunk, end));
      layout.chunkBegin.push_back(static_cast<int>(layout.vertices.size()));
    }
    layout.pieceChunkStart.push_back(layout.chunks());
  }
  return layout;
}

}  // namespace galsculpt
