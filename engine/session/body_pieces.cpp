#include "engine/session/body_pieces.h"

#include "solver/fracture/debris.h"

namespace galsculpt {

void BodyPieces::update(const SimModel& model, const SimState& state) {
  if (revision_ == state.damageRevision) return;
  revision_ = state.damageRevision;
  const PieceCensus& census = tracker_.census(model, state.damaged, state.damageRevision);
  pieces_ = census.pieces;
  pieceNumber_ = census.pieceOfVertex;
  bodyRestVolume_ = census.bodyRestVolume;
  countedTets_ = census.isWhole;
  restVolume_ = census.wholeRestVolume;
  debrisPiece_ = galsculpt::debrisPieces(census, debrisFraction_);
  debrisPieces_ = 0;
  debrisRestVolume_ = 0.0;
  debrisMass_ = 0.0;
  for (int p = 0; p < pieces_; ++p) {
    if (!debrisPiece_[p]) continue;
    ++debrisPieces_;
    debrisRestVolume_ += census.restVolume[p];
  }
  for (int v = 0; v < model.numVertices(); ++v)
    if (debrisPiece_[pieceNumber_[v]]) debrisMass_ += model.mass[v];
}

double BodyPieces::currentVolume(const SimModel& model, const std::vector<Vec3>& x) const {
  double sum = 0.0;
  for (int t = 0; t < model.numTets(); ++t) {
    if (!countedTets_[t]) continue;
    const Tet& tet = model.mesh.tets[t];
    sum += tetSixVolume(x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]) / 6.0;
  }
  return sum;
}

int BodyPieces::invertedPieces(const VisualSurface& surface) const {
  if (pieces_ <= 1) return 0;
  std::vector<double> sixVolume(pieces_, 0.0);
  for (int f = 0; f < surface.mesh.numFaces(); ++f) {
    const Tri& tri = surface.mesh.faces[f];
    const Vec3& a = surface.mesh.vertices[tri[0]];
    sixVolume[pieceNumber_[surface.cellVertex[f]]] +=
        a.dot(surface.mesh.vertices[tri[1]].cross(surface.mesh.vertices[tri[2]]));
  }
  int inverted = 0;
  for (int p = 0; p < pieces_; ++p) {
    if (removesDebris_ && debrisPiece_[p]) continue;
    inverted += !(sixVolume[p] > 0.0);
  }
  return inverted;
}

VisualSurface BodyPieces::withoutRemoved(const VisualSurface& all) const {
  VisualSurface shown;
  std::vector<int> number(all.mesh.numVertices(), -1);
  for (int f = 0; f < all.mesh.numFaces(); ++f) {
    if (removed(all.cellVertex[f])) continue;
    Tri tri = all.mesh.faces[f];
    for (int& v : tri) {
      int& n = number[v];
      if (n < 0) {
        n = shown.mesh.numVertices();
        shown.mesh.vertices.push_back(all.mesh.vertices[v]);
      }
      v = n;
    }
    shown.mesh.faces.push_back(tri);
    shown.tags.push_back(all.tags[f]);
    shown.cellVertex.push_back(all.cellVertex[f]);
  }
  return shown;
}

}  // namespace galsculpt
