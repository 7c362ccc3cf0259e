#include "engine/surface/surface_builder.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "engine/surface/surface_point_keys.h"
#include "solver/frame/timing.h"
#include "solver/mesh/union_find.h"

namespace galsculpt {

using namespace surface_keys;

namespace {

std::int64_t meshCorner(int v) {
  return -static_cast<std::int64_t>(v) - 1;
}
// Keys stay below 2^62, so a key is a non-negative corner until it is turned into a slot.
std::int64_t pointCorner(std::uint64_t key) {
  return static_cast<std::int64_t>(key);
}

// For tet edge k = (i, j): the other two corners (k1, k2) such that (i, j, k1, k2) is an even
// permutation of (0, 1, 2, 3). The quad (midpoint, centroid of face i-j-k1, tet centroid,
// centroid of face i-j-k2) then faces from i towards j.
constexpr int kEdgeOthers[6][2] = {{2, 3}, {3, 1}, {1, 2}, {0, 3}, {2, 0}, {0, 1}};

int localEdgeIndex(int a, int b) {
  for (int k = 0; k < 6; ++k) {
    if ((kTetEdges[k][0] == a && kTetEdges[k][1] == b) ||
        (kTetEdges[k][0] == b && kTetEdges[k][1] == a))
      return k;
  }
  return -1;
}

void buildCsr(int rows, const std::vector<std::pair<int, int>>& pairs, std::vector<int>& start,
              std::vector<int>& list) {
  start.assign(rows + 1, 0);
  for (const auto& [r, c] : pairs) ++start[r + 1];
  for (int r = 0; r < rows; ++r) start[r + 1] += start[r];
  list.resize(pairs.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& [r, c] : pairs) list[fill[r]++] = c;
}

// Groups of a few corners joined by undamaged edges, as bit masks over the corners.
template <int N>
std::array<unsigned, N> cornerGroups(const bool (&joined)[N][N]) {
  int label[N];
  for (int i = 0; i < N; ++i) label[i] = i;
  for (bool changed = true; changed;) {
    changed = false;
    for (int i = 0; i < N; ++i) {
      for (int j = 0; j < N; ++j) {
        if (i != j && joined[i][j] && label[j] < label[i]) {
          label[i] = label[j];
          changed = true;
        }
      }
    }
  }
  std::array<unsigned, N> mask{};
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) {
      if (label[j] == label[i]) mask[i] |= 1u << j;
    }
  }
  return mask;
}

// Where the blade crossed damaged edge e, if a blade did (SimState::crossing).
bool bladeCrossing(const SimModel& model, const SimState& state, int e, Vec3& point) {
  if (!state.damaged[e] || static_cast<size_t>(e) >= state.crossing.size() ||
      !hasCrossing(state.crossing[e]))
    return false;
  const Vec3& a = model.mesh.vertices[model.edges[e][0]];
  const Vec3& b = model.mesh.vertices[model.edges[e][1]];
  point = a + static_cast<double>(state.crossing[e]) * (b - a);
  return true;
}

float crossingSeen(const SimState& state, int e) {
  return static_cast<size_t>(e) < state.crossing.size() ? state.crossing[e] : kNoCrossing;
}

}  // namespace

TriMesh facesWithTag(const VisualSurface& surface, SurfaceTag tag, std::vector<int>* source) {
  TriMesh out;
  if (source) source->clear();
  std::vector<int> map(surface.mesh.vertices.size(), -1);
  for (size_t f = 0; f < surface.mesh.faces.size(); ++f) {
    if (surface.tags[f] != tag) continue;
    Tri tri = surface.mesh.faces[f];
    for (int& v : tri) {
      if (map[v] < 0) {
        map[v] = out.numVertices();
        out.vertices.push_back(surface.mesh.vertices[v]);
        if (source) source->push_back(v);
      }
      v = map[v];
    }
    out.faces.push_back(tri);
  }
  return out;
}

std::vector<Vec3> outerShadingNormals(const VisualSurface& surface) {
  std::vector<Tri> outer;
  for (size_t f = 0; f < surface.mesh.faces.size(); ++f)
    if (surface.tags[f] == SurfaceTag::Outer) outer.push_back(surface.mesh.faces[f]);
  return vertexNormals(surface.mesh.vertices, outer);
}

std::vector<std::pair<int, int>> SurfaceBuilder::numberFaces(const SimModel& model) {
  const TetMesh& mesh = model.mesh;
  const int nT = mesh.numTets();
  // Global face numbering: the sorted corner triple of every tet face.
  struct FaceRef {
    std::array<int, 3> key;
    int tet;
    int corner;  // local corner opposite the face
  };
  std::vector<FaceRef> refs;
  refs.reserve(static_cast<size_t>(nT) * 4);
  for (int t = 0; t < nT; ++t) {
    for (int c = 0; c < 4; ++c) {
      std::array<int, 3> key;
      int n = 0;
      for (int k = 0; k < 4; ++k) {
        if (k != c) key[n++] = mesh.tets[t][k];
      }
      std::sort(key.begin(), key.end());
      refs.push_back({key, t, c});
    }
  }
  std::sort(refs.begin(), refs.end(), [](const FaceRef& a, const FaceRef& b) {
    return a.key != b.key ? a.key < b.key : a.tet < b.tet;
  });
  faceOfTet_.assign(nT, {-1, -1, -1, -1});
  std::vector<std::pair<int, int>> edgeBoundaryPairs;
  for (size_t i = 0; i < refs.size();) {
    size_t j = i + 1;
    while (j < refs.size() && refs[j].key == refs[i].key) ++j;
    const int face = static_cast<int>(faceCorners_.size());
    faceCorners_.push_back(refs[i].key);
    {
      const int t = refs[i].tet, opposite = refs[i].corner;
      std::array<int, 3> edges{};
      int n = 0;
      for (int k = 0; k < 6; ++k) {
        if (kTetEdges[k][0] != opposite && kTetEdges[k][1] != opposite)
          edges[n++] = model.tetEdges[t][k];
      }
      faceEdges_.push_back(edges);
    }
    for (size_t k = i; k < j; ++k) faceOfTet_[refs[k].tet][refs[k].corner] = face;
    if (j - i == 1) {
      const int t = refs[i].tet;
      const Tri outward = tetFacesOutward(mesh.tets[t])[refs[i].corner];
      BoundaryFace b;
      b.corners = outward;
      b.face = face;
      for (int k = 0; k < 3; ++k) {
        int la = -1, lb = -1;
        for (int c = 0; c < 4; ++c) {
          if (mesh.tets[t][c] == outward[k]) la = c;
          if (mesh.tets[t][c] == outward[(k + 1) % 3]) lb = c;
        }
        b.edges[k] = model.tetEdges[t][localEdgeIndex(la, lb)];
        edgeBoundaryPairs.push_back({b.edges[k], static_cast<int>(boundary_.size())});
      }
      boundary_.push_back(b);
    }
    i = j;
  }
  return edgeBoundaryPairs;
}

SurfaceBuilder::SurfaceBuilder(const SimModel& model) {
  const int nT = model.numTets();
  const std::vector<std::pair<int, int>> edgeBoundaryPairs = numberFaces(model);
  std::vector<std::pair<int, int>> edgeTetPairs;
  edgeTetPairs.reserve(static_cast<size_t>(nT) * 6);
  for (int t = 0; t < nT; ++t) {
    for (int k = 0; k < 6; ++k) edgeTetPairs.push_back({model.tetEdges[t][k], t});
  }
  buildCsr(model.numEdges(), edgeTetPairs, edgeTetStart_, edgeTets_);
  buildCsr(model.numEdges(), edgeBoundaryPairs, edgeBoundaryStart_, edgeBoundary_);
  std::vector<std::pair<int, int>> vertexEdgePairs;
  vertexEdgePairs.reserve(static_cast<size_t>(model.numEdges()) * 2);
  for (int e = 0; e < model.numEdges(); ++e) {
    vertexEdgePairs.push_back({model.edges[e][0], e});
    vertexEdgePairs.push_back({model.edges[e][1], e});
  }
  buildCsr(model.numVertices(), vertexEdgePairs, vertexEdgeStart_, vertexEdges_);

  damagedSeen_.assign(model.numEdges(), 0);
  crossingSeen_.assign(model.numEdges(), kNoCrossing);
  slotOfOwner_.assign(boundary_.size() + static_cast<size_t>(nT), -1);
  deformation_.resize(model.numVertices());
}

std::int64_t SurfaceBuilder::acquirePoint(std::uint64_t key) {
  const auto [it, inserted] = pointOfKey_.emplace(key, 0);
  if (inserted) {
    if (!freePoints_.empty()) {
      it->second = freePoints_.back();
      freePoints_.pop_back();
      pointKey_[it->second] = key;
      pointRefs_[it->second] = 0;
    } else {
      it->second = static_cast<std::int64_t>(pointKey_.size());
      pointKey_.push_back(key);
      pointRefs_.push_back(0);
      pointRest_.emplace_back(Vec3::Zero());
    }
  }
  // Every owner using this point is regenerated whenever what places it changes (the damage
  // and crossings of its edge, face or tet): its rest position is refreshed once per update.
  if (pointStamp_.size() < pointKey_.size()) pointStamp_.resize(pointKey_.size(), 0);
  if (pointStamp_[it->second] != updateStamp_) {
    pointStamp_[it->second] = updateStamp_;
    acquiredPoints_.push_back(it->second);
  }
  ++pointRefs_[it->second];
  return it->second;
}

Vec3 SurfaceBuilder::restPoint(const SimModel& model, const SimState& state,
                               std::uint64_t key) const {
  const int index = keyIndex(key);
  const std::vector<Vec3>& X = model.mesh.vertices;
  switch (keyKind(key)) {
    case kEdgePoint: {
      Vec3 p;
      if (bladeCrossing(model, state, index, p)) return p;
      return 0.5 * (X[model.edges[index][0]] + X[model.edges[index][1]]);
    }
    case kFacePoint: {
      // Two damaged edges, both crossed: the blade's trace on this face is the segment between
      // the crossings.
      Vec3 sum = Vec3::Zero(), p;
      int damaged = 0, crossed = 0;
      for (int e : faceEdges_[index]) {
        damaged += state.damaged[e];
        if (bladeCrossing(model, state, e, p)) {
          sum += p;
          ++crossed;
        }
      }
      if (damaged == 2 && crossed == 2) return 0.5 * sum;
      const std::array<int, 3>& c = faceCorners_[index];
      return (X[c[0]] + X[c[1]] + X[c[2]]) / 3.0;
    }
    case kTetPoint: {
      // A clean split (every damaged edge joins the two groups of corners, so the damage is the
      // set of edges a plane through the tet would cut), all crossed: the crossings' mean.
      const Tet& tet = model.mesh.tets[index];
      bool joined[4][4] = {};
      for (int k = 0; k < 6; ++k) {
        const bool intact = !state.damaged[model.tetEdges[index][k]];
        joined[kTetEdges[k][0]][kTetEdges[k][1]] = joined[kTetEdges[k][1]][kTetEdges[k][0]] =
            intact;
      }
      const std::array<unsigned, 4> group = cornerGroups<4>(joined);
      bool clean = group[0] != 0xFu;  // not one group of all four
      for (int i = 0; i < 4 && clean; ++i)
        clean = group[i] == group[0] || group[i] == (0xFu & ~group[0]);  // two groups only
      Vec3 sum = Vec3::Zero(), p;
      int crossed = 0;
      for (int k = 0; k < 6 && clean; ++k) {
        const int e = model.tetEdges[index][k];
        if (!state.damaged[e]) continue;
        if (group[kTetEdges[k][0]] == group[kTetEdges[k][1]] ||
            !bladeCrossing(model, state, e, p)) {
          clean = false;
          break;
        }
        sum += p;
        ++crossed;
      }
      if (clean && crossed > 0) return sum / crossed;
      return 0.25 * (X[tet[0]] + X[tet[1]] + X[tet[2]] + X[tet[3]]);
    }
  }
  return Vec3::Zero();
}

void SurfaceBuilder::releasePoint(std::int64_t corner) {
  if (corner < 0) return;  // mesh vertices are not counted
  if (--pointRefs_[corner] == 0) {
    pointOfKey_.erase(pointKey_[corner]);
    freePoints_.push_back(corner);
  }
}

void SurfaceBuilder::emitBoundaryFace(const SimModel& model,
                                      const std::vector<std::uint8_t>& damaged, int b,
                                      std::vector<PendingTri>& out) {
  const BoundaryFace& bf = boundary_[b];
  bool cut[3];
  bool any = false;
  for (int k = 0; k < 3; ++k) any |= (cut[k] = damaged[bf.edges[k]] != 0);
  if (!any) return;  // the default: the boundary triangle itself

  // Groups of the face's corners, as masks over its sorted corners (the key of its centroid).
  const std::array<int, 3>& sorted = faceCorners_[bf.face];
  auto sortedIndex = [&](int v) { return v == sorted[0] ? 0 : (v == sorted[1] ? 1 : 2); };
  bool joined[3][3] = {};
  for (int k = 0; k < 3; ++k) {
    const int a = sortedIndex(bf.corners[k]), c = sortedIndex(bf.corners[(k + 1) % 3]);
    joined[a][c] = joined[c][a] = !cut[k];
  }
  const std::array<unsigned, 3> group = cornerGroups<3>(joined);
  auto centroid = [&](int v) {
    return pointCorner(pointKey(kFacePoint, bf.face, group[sortedIndex(v)]));
  };
  auto midpoint = [&](int e, int v) {
    return pointCorner(pointKey(kEdgePoint, e, model.edges[e][0] == v ? 1u : 2u));
  };
  for (int k = 0; k < 3; ++k) {
    const int x = bf.corners[k], y = bf.corners[(k + 1) % 3];
    if (!cut[k]) {
      out.push_back({{centroid(x), meshCorner(x), meshCorner(y)}, SurfaceTag::Outer, x});
    } else {
      const int e = bf.edges[k];
      out.push_back({{centroid(x), meshCorner(x), midpoint(e, x)}, SurfaceTag::Outer, x});
      out.push_back({{centroid(y), midpoint(e, y), meshCorner(y)}, SurfaceTag::Outer, y});
    }
  }
}

void SurfaceBuilder::emitTet(const SimModel& model, const std::vector<std::uint8_t>& damaged, int t,
                             std::vector<PendingTri>& out) {
  const Tet& tet = model.mesh.tets[t];
  bool cut[6];
  bool any = false;
  bool joined[4][4] = {};
  for (int k = 0; k < 6; ++k) {
    any |= (cut[k] = damaged[model.tetEdges[t][k]] != 0);
    joined[kTetEdges[k][0]][kTetEdges[k][1]] = joined[kTetEdges[k][1]][kTetEdges[k][0]] = !cut[k];
  }
  if (!any) return;
  const std::array<unsigned, 4> tetGroup = cornerGroups<4>(joined);
  // Exactly two opposite edges damaged: two slits that do not meet, around one group of all
  // four corners. Around the centroid each slit is its own sheet, so each gets its own copy of
  // the centroid (at the same place); one shared copy would be a pinch point.
  const int damagedCount = cut[0] + cut[1] + cut[2] + cut[3] + cut[4] + cut[5];
  const bool twoSlits =
      damagedCount == 2 && ((cut[0] && cut[5]) || (cut[1] && cut[4]) || (cut[2] && cut[3]));

  // Centroid copy of the face opposite local corner `opposite`, on the side of local corner c.
  auto faceCentroid = [&](int opposite, int c) {
    const int face = faceOfTet_[t][opposite];
    const std::array<int, 3>& sorted = faceCorners_[face];
    int local[3];  // local corner of each sorted face corner
    for (int s = 0; s < 3; ++s) {
      for (int q = 0; q < 4; ++q) {
        if (tet[q] == sorted[s]) local[s] = q;
      }
    }
    bool faceJoined[3][3] = {};
    int mine = 0;
    for (int s = 0; s < 3; ++s) {
      if (local[s] == c) mine = s;
      for (int r = 0; r < 3; ++r) faceJoined[s][r] = s != r && joined[local[s]][local[r]];
    }
    return pointCorner(pointKey(kFacePoint, face, cornerGroups<3>(faceJoined)[mine]));
  };
  for (int k = 0; k < 6; ++k) {
    if (!cut[k]) continue;
    const int e = model.tetEdges[t][k];
    const int i = kTetEdges[k][0], j = kTetEdges[k][1];
    const int k1 = kEdgeOthers[k][0], k2 = kEdgeOthers[k][1];
    // Face i-j-k1 is the one opposite k2, and the other way round.
    for (int side = 0; side < 2; ++side) {
      const int c = side == 0 ? i : j;
      const std::int64_t m =
          pointCorner(pointKey(kEdgePoint, e, model.edges[e][0] == tet[c] ? 1u : 2u));
      const std::int64_t center =
          pointCorner(pointKey(kTetPoint, t, tetGroup[c] | (twoSlits && k >= 3 ? 16u : 0u)));
      const std::int64_t f1 = faceCentroid(k2, c);  // face i-j-k1
      const std::int64_t f2 = faceCentroid(k1, c);  // face i-j-k2
      if (side == 0) {
        out.push_back({{m, f1, center}, SurfaceTag::Crack, tet[c]});
        out.push_back({{m, center, f2}, SurfaceTag::Crack, tet[c]});
      } else {
        out.push_back({{m, f2, center}, SurfaceTag::Crack, tet[c]});
        out.push_back({{m, center, f1}, SurfaceTag::Crack, tet[c]});
      }
    }
  }
}

void SurfaceBuilder::regenerateOwner(const SimModel& model, const SimState& state, int owner) {
  std::vector<PendingTri> tris;
  const int nB = static_cast<int>(boundary_.size());
  if (owner < nB) {
    emitBoundaryFace(model, state.damaged, owner, tris);
  } else {
    emitTet(model, state.damaged, owner - nB, tris);
  }
  // Emitters name points by key; stored triangles hold counted point slots.
  for (PendingTri& tri : tris) {
    for (std::int64_t& c : tri.corner) {
      if (c >= 0) c = acquirePoint(static_cast<std::uint64_t>(c));
    }
  }
  int& slot = slotOfOwner_[owner];
  if (slot >= 0) {
    for (const PendingTri& tri : ownerTris_[slot]) {
      for (std::int64_t c : tri.corner) releasePoint(c);
    }
  }
  if (tris.empty()) {
    if (slot >= 0) {
      ownerTris_[slot].clear();
      freeOwnerSlots_.push_back(slot);
      slot = -1;
    }
    return;
  }
  if (slot < 0) {
    if (!freeOwnerSlots_.empty()) {
      slot = freeOwnerSlots_.back();
      freeOwnerSlots_.pop_back();
    } else {
      slot = static_cast<int>(ownerTris_.size());
      ownerTris_.emplace_back();
    }
  }
  ownerTris_[slot] = std::move(tris);
}

void SurfaceBuilder::renumber() {
  surface_.mesh.faces.clear();
  surface_.tags.clear();
  surface_.cellVertex.clear();
  outSource_.clear();
  // Output index of each mesh vertex and point slot, -1 until first used (flat arrays: this
  // runs over every face after each damage change).
  vertexOut_.assign(deformation_.size(), -1);  // one entry per mesh vertex
  pointOut_.assign(pointKey_.size(), -1);
  auto number = [&](std::int64_t source) {
    int& index = source < 0 ? vertexOut_[-source - 1] : pointOut_[source];
    if (index < 0) {
      index = static_cast<int>(outSource_.size());
      outSource_.push_back(source);
    }
    return index;
  };
  auto emit = [&](const PendingTri& tri) {
    surface_.mesh.faces.push_back(
        {number(tri.corner[0]), number(tri.corner[1]), number(tri.corner[2])});
    surface_.tags.push_back(tri.tag);
    surface_.cellVertex.push_back(tri.cellVertex);
  };
  for (size_t owner = 0; owner < slotOfOwner_.size(); ++owner) {
    const int slot = slotOfOwner_[owner];
    if (slot >= 0) {
      for (const PendingTri& tri : ownerTris_[slot]) emit(tri);
    } else if (owner < boundary_.size()) {
      const Tri& c = boundary_[owner].corners;
      emit({{meshCorner(c[0]), meshCorner(c[1]), meshCorner(c[2])}, SurfaceTag::Outer, c[0]});
    }
  }
}

SurfaceUpdateStats SurfaceBuilder::update(const SimModel& model, const SimState& state) {
  SurfaceUpdateStats stats;
  const auto start = Clock::now();
  const bool first = revisionSeen_ == ~0ull;
  if (first || state.damageRevision != revisionSeen_) {
    std::vector<int> owners;
    const int nB = static_cast<int>(boundary_.size());
    for (int e = 0; e < model.numEdges(); ++e) {
      // Crossings compared bit for bit: an undo may bring back the same damage, crossed elsewhere.
      if (state.damaged[e] == damagedSeen_[e] && !state.damaged[e]) continue;
      const float crossing = crossingSeen(state, e);
      if (state.damaged[e] == damagedSeen_[e] &&
          std::memcmp(&crossing, &crossingSeen_[e], sizeof(float)) == 0)
        continue;
      damagedSeen_[e] = state.damaged[e];
      crossingSeen_[e] = crossing;
      for (int k = edgeBoundaryStart_[e]; k < edgeBoundaryStart_[e + 1]; ++k)
        owners.push_back(edgeBoundary_[k]);
      for (int k = edgeTetStart_[e]; k < edgeTetStart_[e + 1]; ++k)
        owners.push_back(nB + edgeTets_[k]);
    }
    std::sort(owners.begin(), owners.end());
    owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
    ++updateStamp_;
    acquiredPoints_.clear();
    for (int owner : owners) regenerateOwner(model, state, owner);
    for (std::int64_t slot : acquiredPoints_) {
      if (pointRefs_[slot] > 0) pointRest_[slot] = restPoint(model, state, pointKey_[slot]);
    }
    stats.rebuiltOwners = static_cast<int>(owners.size());
    stats.topologyChanged = first || !owners.empty();
    if (stats.topologyChanged) {
      renumber();
      preparePlacements(model);
    }
    revisionSeen_ = state.damageRevision;
  }
  stats.msTopology = msSince(start);
  const auto positionsStart = Clock::now();
  evaluatePositions(model, state);
  stats.msPositions = msSince(positionsStart);
  return stats;
}

}  // namespace galsculpt
