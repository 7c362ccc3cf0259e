#include "engine/surface/export_surface.h"

#include <algorithm>
#include <array>
#include <sstream>

#include "engine/surface/solidify.h"
#include "solver/mesh/surface_checks.h"
#include "solver/mesh/surface_parts.h"

namespace galsculpt {

namespace {

// The faces to write: those of each exported piece's outer shell. Fills the report's shell
// counts.
std::vector<int> outerShellFaces(const VisualSurface& all, const std::vector<int>& pieceOfVertex,
                                 ExportedSurface& report) {
  std::vector<int> shellOfFace;
  const int shells = countSurfacePieces(all.mesh, &shellOfFace);
  const std::vector<double> volume = enclosedVolumes(all.mesh, shellOfFace, shells);
  std::vector<int> pieceOfShell(shells, -1);
  for (int f = 0; f < all.mesh.numFaces(); ++f)
    pieceOfShell[shellOfFace[f]] = pieceOfVertex[all.cellVertex[f]];
  int pieceCount = 0;
  for (int p : pieceOfVertex) pieceCount = std::max(pieceCount, p + 1);
  std::vector<int> outer(pieceCount, -1);
  for (int s = 0; s < shells; ++s) {
    const int p = pieceOfShell[s];
    if (p < 0) continue;
    if (outer[p] < 0 || volume[s] > volume[outer[p]]) outer[p] = s;
  }
  std::vector<char> kept(shells, 0);
  for (int p = 0; p < pieceCount; ++p) {
    if (outer[p] < 0) continue;
    kept[outer[p]] = 1;
    ++report.pieces;
    if (!(volume[outer[p]] > 0.0)) ++report.invertedShells;
  }
  for (int s = 0; s < shells; ++s) {
    if (pieceOfShell[s] < 0 || kept[s]) continue;
    if (volume[s] > 0.0) {  // material: a corner carved out, or a part cut off by it
      ++report.detachedShells;
      report.detachedVolume += volume[s];
    } else {  // a cavity: faces turned into the void they close
      ++report.droppedShells;
      report.droppedVolume += std::abs(volume[s]);
    }
  }
  std::vector<int> faces;
  for (int f = 0; f < all.mesh.numFaces(); ++f)
    if (kept[shellOfFace[f]]) faces.push_back(f);
  return faces;
}

// Vertices at one position (two crack-side copies placed alike, e.g. on a knife's plane where
// both sides hold corners with the same centre) would be welded by a reader that merges equal
// positions (STL needs it) into a point where two sheets touch. All but the first of each
// position step 1 % of the way towards the centroid of their faces.
void separateCoincident(TriMesh& mesh) {
  const int n = mesh.numVertices();
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  auto key = [&](int i) {
    const Vec3& p = mesh.vertices[i];
    return std::array<double, 3>{p.x(), p.y(), p.z()};
  };
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return key(a) != key(b) ? key(a) < key(b) : a < b; });
  std::vector<int> stepping;
  for (int k = 1; k < n; ++k)
    if (key(order[k]) == key(order[k - 1])) stepping.push_back(order[k]);
  if (stepping.empty()) return;
  std::vector<Vec3> inward(n, Vec3::Zero());
  std::vector<int> faces(n, 0);
  for (const Tri& f : mesh.faces) {
    const Vec3 centre = (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0;
    for (int v : f) {
      inward[v] += centre;
      ++faces[v];
    }
  }
  for (int v : stepping) mesh.vertices[v] += 0.01 * (inward[v] / faces[v] - mesh.vertices[v]);
}

// Sorts the crossing face pairs of `out.surface` into crossings inside a piece (with the cells
// that bound them) and contact between pieces; sets the volume.
void countCrossings(ExportedSurface& out, const std::vector<std::pair<int, int>>& crossing,
                    const std::vector<int>& pieceOfVertex) {
  const VisualSurface& s = out.surface;
  for (const auto& [f, g] : crossing) {
    const int a = s.cellVertex[f], b = s.cellVertex[g];
    if (pieceOfVertex[a] != pieceOfVertex[b]) {
      ++out.contacts;
      continue;
    }
    ++out.crossings;
    out.crossingCells.push_back(a);
    out.crossingCells.push_back(b);
  }
  std::sort(out.crossingCells.begin(), out.crossingCells.end());
  out.crossingCells.erase(std::unique(out.crossingCells.begin(), out.crossingCells.end()),
                          out.crossingCells.end());
  out.volume = enclosedVolume(s.mesh);
}

}  // namespace

std::string ExportedSurface::summary() const {
  std::ostringstream s;
  s << pieces << " piece(s), " << (crossings == 0 && invertedShells == 0 ? "closed" : "NOT clean");
  if (crossings > 0) s << ", " << crossings << " crossing face pair(s) left";
  if (carveBudgetReached && crossings > 0) {
    s << " (carving them out would leave out more than " << 100.0 * kExportCarveBudget
      << " % of the volume)";
  }
  if (contacts > 0)
    s << ", " << contacts << " face pair(s) of two pieces crossing (pieces overlap)";
  if (invertedShells > 0) s << ", " << invertedShells << " piece(s) inside out";
  if (removedPieces > 0)
    s << "; " << removedPieces << " debris piece(s) removed by the scene's rule, not written";
  if (sealedEdges > 0) s << "; " << sealedEdges << " closed crack edge(s) inside pieces sealed";
  if (carvedCorners > 0)
    s << "; " << carvedCorners << " corner(s) carved out where crack faces crossed";
  if (detachedShells > 0) {
    s << (carvedCorners > 0 ? ", " : "; ") << detachedShells << " detached shell(s) left out ("
      << detachedVolume << " m^3, "
      << 100.0 * detachedVolume / std::max(volume + detachedVolume, 1e-300) << " % of the volume)";
  }
  if (solidifiedPieces > 0) {
    s << "; " << solidifiedPieces
      << " folded piece(s) remade as the boundary of the region they enclose (volume "
      << (solidifiedVolumeChange >= 0.0 ? "+" : "") << solidifiedVolumeChange << " m^3, "
      << 100.0 * solidifiedVolumeChange / std::max(volume, 1e-300) << " %)";
  }
  if (droppedShells > 0) {
    s << "; " << droppedShells << " internal crack shell(s) left out (" << droppedVolume
      << " m^3 enclosed)";
  }
  if (pulledVertices > 0)
    s << "; " << pulledVertices << " crack-face point(s) pulled further apart to clear crossings";
  return s.str();
}

ExportedSurface makeExportSurface(const VisualSurface& all, const std::vector<Vec3>& heldCentre,
                                  const std::vector<int>& pieceOfVertex,
                                  const SurfaceExportOptions& options) {
  ExportedSurface out;
  const std::vector<int> faces = outerShellFaces(all, pieceOfVertex, out);

  // Compact numbering over the kept faces.
  VisualSurface& s = out.surface;
  std::vector<int> number(all.mesh.numVertices(), -1);
  std::vector<int> source;
  for (int f : faces) {
    Tri tri = all.mesh.faces[f];
    for (int& v : tri) {
      if (number[v] < 0) {
        number[v] = static_cast<int>(source.size());
        source.push_back(v);
      }
      v = number[v];
    }
    s.mesh.faces.push_back(tri);
    s.tags.push_back(all.tags[f]);
    s.cellVertex.push_back(all.cellVertex[f]);
  }

  // Crack-side copies stand `separation` of the way towards their held corners; where faces
  // still cross, the copies among their corners are pulled further.
  const size_t n = source.size();
  std::vector<double> pull(n, options.separation);
  std::vector<char> movable(n, 0);
  for (size_t i = 0; i < n; ++i) movable[i] = heldCentre[source[i]] != all.mesh.vertices[source[i]];
  auto place = [&] {
    s.mesh.vertices.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const Vec3& p = all.mesh.vertices[source[i]];
      s.mesh.vertices[i] = movable[i] ? Vec3(p + pull[i] * (heldCentre[source[i]] - p)) : p;
    }
    separateCoincident(s.mesh);
  };
  place();
  constexpr size_t kMaxPairs = 1000000;
  std::vector<std::pair<int, int>> crossing = findSelfIntersections(s.mesh, kMaxPairs);
  for (int round = 0; round < options.rounds && !crossing.empty(); ++round) {
    std::vector<int> raise;
    for (const auto& [f, g] : crossing) {
      for (int face : {f, g}) {
        for (int v : s.mesh.faces[face])
          if (movable[v] && pull[v] < options.maxSeparation) raise.push_back(v);
      }
    }
    if (raise.empty()) break;
    std::sort(raise.begin(), raise.end());
    raise.erase(std::unique(raise.begin(), raise.end()), raise.end());
    std::vector<char> moved(n, 0);
    for (int v : raise) {
      pull[v] = std::min(2.0 * pull[v], options.maxSeparation);
      moved[v] = 1;
    }
    place();
    // Only pairs with a moved face can have changed: those are checked again, the others that
    // crossed still do.
    std::vector<char> movedFace(s.mesh.faces.size(), 0);
    for (size_t f = 0; f < s.mesh.faces.size(); ++f)
      for (int v : s.mesh.faces[f]) movedFace[f] |= moved[v];
    std::vector<std::pair<int, int>> still = findSelfIntersections(s.mesh, kMaxPairs, &movedFace);
    for (const auto& pair : crossing)
      if (!movedFace[pair.first] && !movedFace[pair.second]) still.push_back(pair);
    std::sort(still.begin(), still.end());
    crossing = std::move(still);
  }
  countCrossings(out, crossing, pieceOfVertex);
  for (size_t i = 0; i < n; ++i) out.pulledVertices += movable[i] && pull[i] > options.separation;
  return out;
}

void solidifyCrossingPieces(ExportedSurface& out, const std::vector<int>& pieceOfVertex) {
  if (out.crossings == 0) return;
  std::vector<char> folded(pieceOfVertex.size(), 0);
  for (int v : out.crossingCells) folded[pieceOfVertex[v]] = 1;
  const VisualSurface& before = out.surface;
  VisualSurface after;
  std::vector<int> number(before.mesh.numVertices(), -1);
  // The faces of `piece` (or of every piece not folded, with -1) appended to `to` with their
  // own numbering.
  auto copyFaces = [&](int piece, VisualSurface& to) {
    std::fill(number.begin(), number.end(), -1);
    for (int f = 0; f < before.mesh.numFaces(); ++f) {
      const int p = pieceOfVertex[before.cellVertex[f]];
      if (piece >= 0 ? p != piece : folded[p] != 0) continue;
      Tri tri = before.mesh.faces[f];
      for (int& v : tri) {
        if (number[v] < 0) {
          number[v] = to.mesh.numVertices();
          to.mesh.vertices.push_back(before.mesh.vertices[v]);
        }
        v = number[v];
      }
      to.mesh.faces.push_back(tri);
      to.tags.push_back(before.tags[f]);
      to.cellVertex.push_back(before.cellVertex[f]);
    }
  };
  copyFaces(-1, after);
  for (int piece = 0; piece < static_cast<int>(folded.size()); ++piece) {
    if (!folded[piece]) continue;
    VisualSurface shell;
    copyFaces(piece, shell);
    std::vector<double> edges;
    for (const Tri& f : shell.mesh.faces)
      for (int k = 0; k < 3; ++k)
        edges.push_back((shell.mesh.vertices[f[k]] - shell.mesh.vertices[f[(k + 1) % 3]]).norm());
    std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
    const double cell = edges[edges.size() / 2];
    TriMesh solid = solidify(shell.mesh, {.cell = cell, .maxNodes = 4000000});
    std::vector<int> shellOfFace;
    const int shells = countSurfacePieces(solid, &shellOfFace);
    const std::vector<double> volume = enclosedVolumes(solid, shellOfFace, shells);
    const int keptShell =
        shells == 0
            ? -1
            : static_cast<int>(std::max_element(volume.begin(), volume.end()) - volume.begin());
    if (keptShell < 0 || !(volume[keptShell] > 0.0)) {  // thinner than the grid: left as it was
      appendSurface(after.mesh, shell.mesh);
      after.tags.insert(after.tags.end(), shell.tags.begin(), shell.tags.end());
      after.cellVertex.insert(after.cellVertex.end(), shell.cellVertex.begin(),
                              shell.cellVertex.end());
      continue;
    }
    for (int s = 0; s < shells; ++s) {
      if (s == keptShell) continue;
      if (volume[s] > 0.0) {
        ++out.detachedShells;
        out.detachedVolume += volume[s];
      } else {
        ++out.droppedShells;
        out.droppedVolume += std::abs(volume[s]);
      }
    }
    const TriMesh kept = facesOfGroup(solid, shellOfFace, keptShell);
    ++out.solidifiedPieces;
    out.solidifiedVolumeChange += enclosedVolume(kept) - enclosedVolume(shell.mesh);
    appendSurface(after.mesh, kept);
    after.tags.resize(after.mesh.faces.size(), SurfaceTag::Outer);
    after.cellVertex.resize(after.mesh.faces.size(), shell.cellVertex[0]);
  }
  out.surface = std::move(after);
  out.crossings = 0;
  out.contacts = 0;
  out.crossingCells.clear();
  countCrossings(out, findSelfIntersections(out.surface.mesh, 1000000), pieceOfVertex);
}

}  // namespace galsculpt
