// Closed surface -> tet mesh with about N tets, by running the `tetgen` program.
//
// TetGen runs as a subprocess with a time limit: it aborts on bad input and is AGPL, so it stays
// out of our process. The surface is checked first (open, non-manifold, self-intersecting input
// gets an error that says which). The volume bound (-a) is searched in log space until the tet
// count lands within the tolerance of the target: counts jump with the bound, so a single guess
// from volume / N is never enough. Where the count jumps across the target within a 1 % change
// of the bound, the quality bound is nudged (a few percent) and the search resumes. A surface
// finer than N tets allow (a scanned model with 50k triangles meshed to 40k tets) first forces
// more tets than wanted. Then, in order: keep the surface as given (-Y); simplify the surface
// (quadric edge collapses, to about one face per 12 tets, more where fewer would stray beyond
// kShapeVolume or kShapeDistance of its shape; each try said) and try the strict levels again;
// relax the radius-edge bound step by step. Each level is probed once without a volume bound.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// How far a simplified surface may stray from the one given before it is meshed: its enclosed
// volume, relative, and the farthest distance between the two, relative to the bounding-box
// diagonal. A simplification beyond either keeps more faces, or is not used.
inline constexpr double kShapeVolume = 0.01;
inline constexpr double kShapeDistance = 0.01;

struct TetrahedralizeOptions {
  int targetTets = 10000;
  double tolerance = 0.15;         // accept counts within +-15 % of targetTets
  double radiusEdgeRatio = 1.414;  // TetGen -q quality bound
  double timeoutSeconds = 300.0;   // per TetGen run
  int maxAttempts = 30;
  std::string program = "tetgen";
  std::string surfaceName = "surface";  // used in messages
  // A simplification must keep the shape (kShapeVolume, kShapeDistance). Off for a generator's
  // own surface, made for the count asked: a 100-tet sphere is a coarse sphere by request.
  bool keepShape = true;
  // A surface that crosses itself (shells through each other: pieces of an export that overlap,
  // a model whose parts interpenetrate) is meshed as the region it encloses, remade free of
  // crossings on a grid of half the target tets' edge (solidify.h), and said; off, it is refused.
  bool solidifyCrossings = true;
  std::function<void(const std::string&)> progress;  // one line per attempt, optional
};

// How strictly TetGen shapes the tets: a radius-edge bound (0 = none) and whether the input
// surface is kept as given (-Y: no Steiner points on it).
struct TetQuality {
  double radiusEdgeRatio = 1.414;
  bool keepSurface = false;
};

struct TetrahedralizeResult {
  TetMesh mesh;
  double volumeBound = 0.0;  // 0: none was needed
  TetQuality quality;
  int attempts = 0;
};

// No volume bound made TetGen reach the requested count within the tolerance: the count, not
// TetGen, is what to change. `closest` is the nearest count it reached.
struct TetCountUnreachable : std::runtime_error {
  TetCountUnreachable(const std::string& what, int closest)
      : std::runtime_error(what), closest(closest) {}
  int closest;
};

// Throws InputError for a bad surface, TetCountUnreachable when no bound reaches the target,
// std::runtime_error when TetGen fails, crashes or times out.
TetrahedralizeResult tetrahedralize(const TriMesh& surface, const TetrahedralizeOptions& options);

// The first of `surfaces` (resolutions of one shape, the preferred one first) whose
// tetrahedralization reaches the count: TetGen's refinement jumps over some counts on one
// surface and reaches them on a finer one. Throws the TetCountUnreachable whose closest count
// is nearest the target when none does.
TetrahedralizeResult tetrahedralizeAny(const std::vector<TriMesh>& surfaces,
                                       const TetrahedralizeOptions& options);

// What TetGen takes for each tet it makes (its pools of tets, faces, points and their links;
// docs/notes/2026-12-07-memory-before-starting.md).
inline constexpr double kTetgenBytesPerTet = 500.0;
// Throws OutOfMemory (memory_limits.h) with the size when meshing to `tets` would need more
// than the memory available; `name` is the surface's, for the message.
void checkMemoryForTets(long long tets, const std::string& name);

// Throws InputError naming the first problem of a surface that TetGen cannot mesh (with
// `crossings` false, all but crossing faces).
void checkMeshableSurface(const TriMesh& surface, const std::string& name, bool crossings = true);

}  // namespace galsculpt
