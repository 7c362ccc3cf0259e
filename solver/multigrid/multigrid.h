// Galerkin multigrid for the backward-Euler system (paper section 3.2-3.3, Algorithm 2).
//
// Hierarchy (built once per mesh): farthest-point sampling with geodesic distances (Dijkstra
// on the rest edge graph) from a fixed seed picks k_1 > k_2 > ... handles, each level a subset
// of the one above. Every vertex (or handle) belongs to its geodesically nearest handle of the
// next level: piecewise-constant skinning weights. Each handle carries an affine map T (3x4,
// 12 DOFs) acting on positions relative to the handle, so U_1 has one 3x12 block per fine
// vertex and U_l (l > 1) one 12x12 block per handle. R_l = U_l^T and A_{l+1} = U_l^T A_l U_l,
// refreshed from the current stiffness every frame (values only; the patterns are fixed).
//
// This file is the precomputation: the hierarchy, rebuilt only when damage splits aggregates
// (updateDamage). The solve on it (refresh, V-cycles with block Gauss-Seidel or Jacobi, CG or a
// dense Cholesky on the coarsest level, PCG) is multigrid_cycle.h, run by either executor.
//
// Aggregates too small or too flat to carry 12 affine DOFs: U has a null space there (affine
// modes that move no fine vertex). A relative 1e-9 shift on each coarse diagonal block makes
// those modes solvable; they never reach the fine level, so the fine solution is unchanged.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/fem/block_sparse.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// Farthest-point sampling of `count` vertices among `candidates` with geodesic distances over
// the edge graph; the first sample is the candidate farthest from candidates[0] (deterministic).
// Also returns, for every vertex, its nearest sample (index into the result) in `nearest`.
std::vector<int> farthestPointSamples(const std::vector<Vec3>& points,
                                      const std::vector<Edge>& edges,
                                      const std::vector<int>& candidates, int count,
                                      std::vector<int>* nearest);

struct MultigridLevel {
  int handles = 0;
  std::vector<int> handleVertex;   // (handles) the sampled vertex of each handle
  std::vector<int> origin;         // (handles) the base aggregate (sample) it was split from
  std::vector<int> parent;         // (rows of the finer level) handle of this level
  std::vector<Eigen::Vector4d> y;  // level 1: (fine vertices) [(x - c_parent)/s; 1]
  std::vector<Eigen::Matrix<double, 12, 12>> toParent;  // levels > 1: (finer handles) 12x12 U block
  // Coarse operator's pattern: handle-by-handle 12x12 blocks over the handle adjacency (the
  // values live with the cycle, multigrid_cycle.h).
  std::vector<int> rowStart, columns;  // block CSR
  // For level 1, the fine block (index into the fine pattern) -> coarse block map.
  std::vector<int> fineToCoarseBlock;
  std::vector<int> finerToCoarseBlock;    // levels > 1: finer coarse block -> this level's block
  std::vector<std::vector<int>> colors;   // handles grouped for parallel Gauss-Seidel
  std::vector<std::vector<int>> members;  // (handles) rows of the finer level in each aggregate
};

class Multigrid {
 public:
  // `fine` is the fine-level pattern, `restPositions` the rest mesh, `edges` its edge graph.
  Multigrid(const BlockPattern& fine, const std::vector<Vec3>& restPositions,
            const std::vector<Edge>& edges, const std::vector<int>& handleCounts);

  // Crack-aware aggregates: splits every base aggregate into its connected parts over the
  // undamaged edges (a part that holds no sample gets its own handle), so that no handle glues
  // pieces together. Does nothing when `revision` was seen already; returns whether the
  // hierarchy changed. Call refresh() afterwards.
  bool updateDamage(const std::vector<Edge>& edges, const std::vector<std::uint8_t>& damaged,
                    std::uint64_t revision);
  std::uint64_t damageRevision() const { return damageRevision_; }

  int numLevels() const { return static_cast<int>(levels_.size()); }
  const MultigridLevel& level(int l) const { return levels_[l]; }
  // Dense U of level l (for tests): rows = finer DOFs, columns = 12 * handles.
  Eigen::MatrixXd prolongationMatrix(int l) const;

  // Read access for the cycle, which mirrors the hierarchy (multigrid_layout.h).
  const std::vector<std::vector<int>>& fineColors() const { return fineColors_; }
  const std::vector<Vec3>& restPositions() const { return rest_; }
  const std::vector<int>& fragmentStart() const { return fragmentStart_; }  // CSR over fragments
  const std::vector<int>& fragmentVertices() const { return fragmentVertices_; }
  Vec3 fragmentCenter(int f) const { return fragments_[f].center; }
  double fragmentScale(int f) const { return fragments_[f].scale; }
  // Pieces of the coarsest handles (0 unless two or more pieces hold handles), each handle's
  // piece and its affine map from the piece's frame.
  int pieceCount() const { return pieceCount_; }
  const std::vector<int>& pieceOfHandle() const { return piece_; }
  const std::vector<Eigen::Matrix<double, 12, 12>>& pieceMaps() const { return pieceMap_; }

 private:
  struct BaseLevel {
    std::vector<int> samples;    // farthest-point samples (fine vertex indices)
    std::vector<int> sampleRow;  // each sample's row in the finer level
    std::vector<int> nearest;    // (fine vertices) nearest sample
    double scale = 1.0;          // typical aggregate size, for the local frames
  };
  // Aggregates of every level from the base samples, split over undamaged edges when `damaged`
  // is given; returns whether any assignment changed.
  // `vertexPiece` (each vertex's piece) is read only with damage.
  bool assignAggregates(const std::vector<Edge>& edges, const std::vector<std::uint8_t>* damaged,
                        const std::vector<int>& vertexPiece);
  void buildLevelStructures();
  // Pieces of the coarsest handles and their affine maps (empty `vertexPiece`: undamaged).
  void assignCoarsestPieces(const std::vector<int>& vertexPiece);
  // Pieces too small for coarse handles (but more than one vertex), and their correction.
  void collectFragments(const std::vector<int>& vertexPiece);
  struct FragmentFrame {
    Vec3 center = Vec3::Zero();
    double scale = 1.0;
  };
  std::vector<int> fragmentStart_{0}, fragmentVertices_;  // CSR: vertices of each fragment
  std::vector<int> fragmentOf_;                           // (nVerts) fragment, -1: none
  std::vector<FragmentFrame> fragments_;                  // (nFragments)

  const BlockPattern* finePattern_;
  std::vector<Vec3> rest_;
  std::vector<BaseLevel> base_;
  std::uint64_t damageRevision_ = 0;
  std::vector<std::vector<int>> fineColors_;
  std::vector<MultigridLevel> levels_;
  // Per-piece coarse correction (only with two or more pieces holding handles).
  int pieceCount_ = 0;
  std::vector<int> piece_;                               // (coarsest handles) piece
  std::vector<Eigen::Matrix<double, 12, 12>> pieceMap_;  // (coarsest handles) piece -> handle
};

}  // namespace galsculpt
