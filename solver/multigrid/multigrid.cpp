#include "solver/multigrid/multigrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <stdexcept>

#include "solver/mesh/union_find.h"

namespace galsculpt {

namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

// Smallest damage fragment that gets coarse handles. Smaller ones are corrected in their own
// affine modes (correctFragments) and by the fine smoother.
constexpr int kMinFragment = 64;

Mat12 kron4x3(const Eigen::Matrix4d& m, const Eigen::Matrix3d& a) {
  Mat12 out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out.block<3, 3>(3 * i, 3 * j) = m(i, j) * a;
  }
  return out;
}

// Greedy colouring of a symmetric block pattern given as CSR (row -> neighbour rows).
std::vector<std::vector<int>> colorRows(int rows, const std::vector<int>& rowStart,
                                        const std::vector<int>& columns) {
  std::vector<int> color(rows, -1);
  std::vector<std::vector<int>> groups;
  std::vector<char> used;
  for (int r = 0; r < rows; ++r) {
    used.assign(groups.size() + 1, 0);
    for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
      const int c = color[columns[k]];
      if (c >= 0) used[c] = 1;
    }
    int c = 0;
    while (used[c]) ++c;
    color[r] = c;
    if (c >= static_cast<int>(groups.size())) groups.resize(c + 1);
    groups[c].push_back(r);
  }
  return groups;
}

// Builds a block CSR over pairs (row, column) and returns, for each input pair, its block.
void buildCoarsePattern(int rows, const std::vector<std::pair<int, int>>& pairs,
                        std::vector<int>& rowStart, std::vector<int>& columns,
                        std::vector<int>& blockOfPair) {
  std::vector<std::vector<int>> cols(rows);
  for (const auto& [r, c] : pairs) {
    if (r >= 0 && c >= 0) cols[r].push_back(c);
  }
  // Every row keeps its diagonal block, even a handle left without rows (its regularization
  // lives there).
  for (int r = 0; r < rows; ++r) cols[r].push_back(r);
  rowStart.assign(rows + 1, 0);
  for (int r = 0; r < rows; ++r) {
    std::sort(cols[r].begin(), cols[r].end());
    cols[r].erase(std::unique(cols[r].begin(), cols[r].end()), cols[r].end());
    rowStart[r + 1] = rowStart[r] + static_cast<int>(cols[r].size());
  }
  columns.clear();
  for (int r = 0; r < rows; ++r) columns.insert(columns.end(), cols[r].begin(), cols[r].end());
  blockOfPair.resize(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    const auto [r, c] = pairs[i];
    if (r < 0 || c < 0) {
      blockOfPair[i] = -1;  // a row without a coarse handle
      continue;
    }
    const auto begin = columns.begin() + rowStart[r], end = columns.begin() + rowStart[r + 1];
    blockOfPair[i] = static_cast<int>(std::lower_bound(begin, end, c) - columns.begin());
  }
}

double levelScale(const std::vector<Vec3>& points, int handles) {
  const BoundingBox box = boundingBox(points);
  const Vec3 size = box.size().cwiseMax(1e-12 * std::max(1.0, box.size().maxCoeff()));
  return std::max(std::cbrt(size.prod() / std::max(handles, 1)), 1e-300);
}

}  // namespace

std::vector<int> farthestPointSamples(const std::vector<Vec3>& points,
                                      const std::vector<Edge>& edges,
                                      const std::vector<int>& candidates, int count,
                                      std::vector<int>* nearest) {
  const int n = static_cast<int>(points.size());
  std::vector<int> start(n + 1, 0), adj(2 * edges.size());
  std::vector<double> weight(2 * edges.size());
  for (const Edge& e : edges) {
    ++start[e[0] + 1];
    ++start[e[1] + 1];
  }
  for (int i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const Edge& e : edges) {
    const double w = (points[e[0]] - points[e[1]]).norm();
    adj[fill[e[0]]] = e[1];
    weight[fill[e[0]]++] = w;
    adj[fill[e[1]]] = e[0];
    weight[fill[e[1]]++] = w;
  }
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(n, inf);
  std::vector<int> label(n, -1);
  using Item = std::pair<double, int>;
  auto grow = [&](int source, int id, std::vector<double>& d, std::vector<int>* lab) {
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    d[source] = 0.0;
    if (lab) (*lab)[source] = id;
    heap.push({0.0, source});
    while (!heap.empty()) {
      const auto [du, u] = heap.top();
      heap.pop();
      if (du > d[u]) continue;
      for (int k = start[u]; k < start[u + 1]; ++k) {
        const double nd = du + weight[k];
        const int v = adj[k];
        if (nd < d[v]) {
          d[v] = nd;
          if (lab) (*lab)[v] = id;
          heap.push({nd, v});
        }
      }
    }
  };
  count = std::min<int>(count, static_cast<int>(candidates.size()));
  std::vector<int> samples;
  if (count <= 0) return samples;
  // Fixed seed: the candidate farthest from the first candidate.
  {
    std::vector<double> d0(n, inf);
    grow(candidates[0], 0, d0, nullptr);
    int first = candidates[0];
    double best = -1.0;
    for (int c : candidates) {
      const double d = std::isinf(d0[c]) ? std::numeric_limits<double>::max() : d0[c];
      if (d > best) {
        best = d;
        first = c;
      }
    }
    samples.push_back(first);
    grow(first, 0, dist, &label);
  }
  while (static_cast<int>(samples.size()) < count) {
    int next = -1;
    double best = -1.0;
    for (int c : candidates) {
      const double d = std::isinf(dist[c]) ? std::numeric_limits<double>::max() : dist[c];
      if (d > best) {
        best = d;
        next = c;
      }
    }
    if (best <= 0.0) break;  // every candidate is already a sample
    samples.push_back(next);
    grow(next, static_cast<int>(samples.size()) - 1, dist, &label);
  }
  // Vertices in components without a sample join the first handle (they carry no coupling).
  for (int& l : label) {
    if (l < 0) l = 0;
  }
  if (nearest) *nearest = std::move(label);
  return samples;
}

Multigrid::Multigrid(const BlockPattern& fine, const std::vector<Vec3>& rest,
                     const std::vector<Edge>& edges, const std::vector<int>& handleCounts)
    : finePattern_(&fine), rest_(rest) {
  fineColors_ = colorRows(fine.rows, fine.rowStart, fine.columns);
  std::vector<int> candidates(rest.size());
  for (size_t i = 0; i < rest.size(); ++i) candidates[i] = static_cast<int>(i);
  for (size_t l = 0; l < handleCounts.size(); ++l) {
    BaseLevel base;
    base.samples = farthestPointSamples(rest, edges, candidates, handleCounts[l], &base.nearest);
    base.scale = levelScale(rest, static_cast<int>(base.samples.size()));
    // Each sample's row in the finer level (its index among the candidates).
    std::vector<int> rowOfVertex(rest.size(), -1);
    for (size_t i = 0; i < candidates.size(); ++i) rowOfVertex[candidates[i]] = static_cast<int>(i);
    for (int v : base.samples) base.sampleRow.push_back(rowOfVertex[v]);
    candidates = base.samples;
    base_.push_back(std::move(base));
  }
  levels_.resize(base_.size());
  assignAggregates(edges, nullptr, {});
  buildLevelStructures();
}

bool Multigrid::assignAggregates(const std::vector<Edge>& edges,
                                 const std::vector<std::uint8_t>* damaged,
                                 const std::vector<int>& vertexPiece) {
  const int n = static_cast<int>(rest_.size());
  std::vector<int> fineToRow(n);
  for (int v = 0; v < n; ++v) fineToRow[v] = v;
  bool changed = false;
  for (size_t l = 0; l < base_.size(); ++l) {
    const BaseLevel& base = base_[l];
    const int rows = l == 0 ? n : levels_[l - 1].handles;
    std::vector<int> rowBase(rows), rowVertex(rows);
    for (int r = 0; r < rows; ++r) {
      rowVertex[r] = l == 0 ? r : levels_[l - 1].handleVertex[r];
      rowBase[r] =
          l == 0 ? base.nearest[r] : base.nearest[base_[l - 1].samples[levels_[l - 1].origin[r]]];
    }
    // Rows of one base aggregate joined by undamaged edges form one handle; without damage
    // the aggregate is the base one, whole.
    UnionFind components(rows);
    if (damaged) {
      for (size_t e = 0; e < edges.size(); ++e) {
        if ((*damaged)[e]) continue;
        const int a = fineToRow[edges[e][0]], b = fineToRow[edges[e][1]];
        if (a >= 0 && b >= 0 && a != b && rowBase[a] == rowBase[b]) components.unite(a, b);
      }
    } else {
      std::vector<int> first(base.samples.size(), -1);
      for (int r = 0; r < rows; ++r) {
        int& f = first[rowBase[r]];
        if (f < 0) f = r;
        components.unite(f, r);
      }
    }
    // The part holding the base sample keeps the base handle's index, so that an undamaged
    // mesh gets the base hierarchy; other parts are appended in row order (deterministic).
    std::vector<int> idOfRoot(rows, -1);
    std::vector<int> handleVertex(base.samples.begin(), base.samples.end());
    std::vector<int> origin(base.samples.size());
    for (size_t h = 0; h < base.samples.size(); ++h) {
      idOfRoot[components.find(base.sampleRow[h])] = static_cast<int>(h);
      origin[h] = static_cast<int>(h);
    }
    // Pieces of fewer than kMinFragment vertices get no handle (parent -1): giving each one
    // would grow the coarse levels with every crack (hundreds of loose vertices and small
    // fragments after many cuts: at 100 cuts on the sphere the solve took 2.3 times as long
    // with 4 as the limit). A lone vertex is solved by the fine smoother; a small fragment
    // also by a correction in its own affine modes (correctFragments), which moves it as a
    // whole.
    // Only whole pieces that small are left out: a small part of a large piece still needs
    // the coarse correction that moves the piece.
    std::vector<int> pieceSize(rows, 0);
    if (l == 0 && damaged) {
      for (int r = 0; r < rows; ++r) ++pieceSize[vertexPiece[r]];
    }
    std::vector<int> parent(rows);
    for (int r = 0; r < rows; ++r) {
      const int root = components.find(r);
      if (l == 0 && damaged && pieceSize[vertexPiece[r]] < kMinFragment) {
        parent[r] = -1;
        continue;
      }
      int& id = idOfRoot[root];
      if (id < 0) {
        id = static_cast<int>(handleVertex.size());
        handleVertex.push_back(rowVertex[r]);
        origin.push_back(rowBase[r]);
      }
      parent[r] = id;
    }
    MultigridLevel& level = levels_[l];
    if (level.parent != parent || level.handleVertex != handleVertex) changed = true;
    level.parent = std::move(parent);
    level.handleVertex = std::move(handleVertex);
    level.origin = std::move(origin);
    level.handles = static_cast<int>(level.handleVertex.size());
    for (int& r : fineToRow) r = r >= 0 ? level.parent[r] : -1;
  }
  return changed;
}

void Multigrid::buildLevelStructures() {
  const BlockPattern& fine = *finePattern_;
  for (size_t l = 0; l < levels_.size(); ++l) {
    MultigridLevel& level = levels_[l];
    const double scale = base_[l].scale;
    std::vector<Vec3> centers(level.handles);
    for (int h = 0; h < level.handles; ++h) centers[h] = rest_[level.handleVertex[h]];
    std::vector<std::pair<int, int>> pairs;
    if (l == 0) {
      level.y.resize(rest_.size());
      for (size_t v = 0; v < rest_.size(); ++v) {
        if (level.parent[v] < 0) {
          level.y[v].setZero();
          continue;
        }
        level.y[v] << (rest_[v] - centers[level.parent[v]]) / scale, 1.0;
      }
      pairs.reserve(fine.columns.size());
      for (int r = 0; r < fine.rows; ++r) {
        for (int k = fine.rowStart[r]; k < fine.rowStart[r + 1]; ++k) {
          pairs.push_back({level.parent[r], level.parent[fine.columns[k]]});
        }
      }
      buildCoarsePattern(level.handles, pairs, level.rowStart, level.columns,
                         level.fineToCoarseBlock);
    } else {
      const MultigridLevel& finer = levels_[l - 1];
      const double finerScale = base_[l - 1].scale;
      level.toParent.resize(finer.handles);
      for (int a = 0; a < finer.handles; ++a) {
        const int b = level.parent[a];
        Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
        m.topLeftCorner<3, 3>() *= finerScale / scale;
        m.block<3, 1>(0, 3) = (rest_[finer.handleVertex[a]] - centers[b]) / scale;
        level.toParent[a] = kron4x3(m.transpose(), Eigen::Matrix3d::Identity());
      }
      for (int r = 0; r < finer.handles; ++r) {
        for (int k = finer.rowStart[r]; k < finer.rowStart[r + 1]; ++k) {
          pairs.push_back({level.parent[r], level.parent[finer.columns[k]]});
        }
      }
      buildCoarsePattern(level.handles, pairs, level.rowStart, level.columns,
                         level.finerToCoarseBlock);
    }
    level.colors = colorRows(level.handles, level.rowStart, level.columns);
    level.members.assign(level.handles, {});
    for (size_t r = 0; r < level.parent.size(); ++r) {
      if (level.parent[r] >= 0) level.members[level.parent[r]].push_back(static_cast<int>(r));
    }
  }
}

bool Multigrid::updateDamage(const std::vector<Edge>& edges,
                             const std::vector<std::uint8_t>& damaged, std::uint64_t revision) {
  if (revision == damageRevision_) return false;
  damageRevision_ = revision;
  const bool anyDamage = std::find(damaged.begin(), damaged.end(), 1) != damaged.end();
  // Each vertex's piece (a representative vertex), found once for both uses below.
  std::vector<int> vertexPiece;
  if (anyDamage) {
    UnionFind uf(static_cast<int>(rest_.size()));
    for (size_t e = 0; e < edges.size(); ++e) {
      if (!damaged[e]) uf.unite(edges[e][0], edges[e][1]);
    }
    vertexPiece.resize(rest_.size());
    for (size_t v = 0; v < rest_.size(); ++v) vertexPiece[v] = uf.find(static_cast<int>(v));
  }
  const bool handlesChanged = assignAggregates(edges, anyDamage ? &damaged : nullptr, vertexPiece);
  if (handlesChanged) buildLevelStructures();
  // The pieces and fragments follow the damage also where the handles stay (a fragment that
  // crumbles into loose vertices has no handle to change): kept from before, they made a frame
  // depend on the order the damage came in, and a fresh solver (a reopened project) ran on
  // differently from one that had stepped through it.
  const std::vector<int> piecesBefore = piece_, fragmentsBefore = fragmentVertices_,
                         fragmentStartBefore = fragmentStart_;
  assignCoarsestPieces(vertexPiece);
  collectFragments(vertexPiece);
  return handlesChanged || piece_ != piecesBefore || fragmentVertices_ != fragmentsBefore ||
         fragmentStart_ != fragmentStartBefore;
}

void Multigrid::collectFragments(const std::vector<int>& vertexPiece) {
  fragmentStart_.assign(1, 0);
  fragmentVertices_.clear();
  fragments_.clear();
  fragmentOf_.assign(rest_.size(), -1);
  if (vertexPiece.empty()) return;
  // Pieces without a coarse handle and of more than one vertex (a lone vertex's block solve in
  // the smoother is already exact for its translation), grouped by a counting sort on pieces.
  std::vector<int> count(rest_.size() + 1, 0);
  for (size_t v = 0; v < rest_.size(); ++v) {
    if (levels_[0].parent[v] < 0) ++count[vertexPiece[v] + 1];
  }
  for (size_t piece = 0; piece < rest_.size(); ++piece) {
    if (count[piece + 1] < 2) count[piece + 1] = 0;  // lone vertices: not a fragment
  }
  std::vector<int> fragmentOfPiece(rest_.size(), -1);
  for (size_t piece = 0; piece < rest_.size(); ++piece) {
    if (count[piece + 1] == 0) continue;
    fragmentOfPiece[piece] = static_cast<int>(fragmentStart_.size()) - 1;
    fragmentStart_.push_back(fragmentStart_.back() + count[piece + 1]);
  }
  fragmentVertices_.resize(fragmentStart_.back());
  std::vector<int> fill(fragmentStart_.begin(), fragmentStart_.end() - 1);
  for (size_t v = 0; v < rest_.size(); ++v) {
    const int f = levels_[0].parent[v] < 0 ? fragmentOfPiece[vertexPiece[v]] : -1;
    if (f < 0) continue;
    fragmentOf_[v] = f;
    fragmentVertices_[fill[f]++] = static_cast<int>(v);
  }
  // Each fragment's frame for its affine modes y_v = [(X_v - c) / scale, 1].
  fragments_.resize(fragmentStart_.size() - 1);
  for (size_t f = 0; f < fragments_.size(); ++f) {
    FragmentFrame& fc = fragments_[f];
    fc.center.setZero();
    for (int i = fragmentStart_[f]; i < fragmentStart_[f + 1]; ++i)
      fc.center += rest_[fragmentVertices_[i]];
    fc.center /= fragmentStart_[f + 1] - fragmentStart_[f];
    fc.scale = 0.0;
    for (int i = fragmentStart_[f]; i < fragmentStart_[f + 1]; ++i)
      fc.scale = std::max(fc.scale, (rest_[fragmentVertices_[i]] - fc.center).norm());
    if (fc.scale <= 0.0) fc.scale = 1.0;
  }
}

void Multigrid::assignCoarsestPieces(const std::vector<int>& vertexPiece) {
  piece_.clear();
  pieceCount_ = 0;
  if (vertexPiece.empty()) return;
  const MultigridLevel& coarsest = levels_.back();
  std::vector<int> idOfRoot(rest_.size(), -1);
  piece_.resize(coarsest.handles);
  for (int h = 0; h < coarsest.handles; ++h) {
    int& id = idOfRoot[vertexPiece[coarsest.handleVertex[h]]];
    if (id < 0) id = pieceCount_++;
    piece_[h] = id;
  }
  if (pieceCount_ < 2) {
    piece_.clear();
    pieceCount_ = 0;
    return;
  }
  // Each handle's affine map as seen from its piece's frame (centre: the piece's first handle).
  std::vector<int> centerVertex(pieceCount_, -1);
  for (int h = 0; h < coarsest.handles; ++h) {
    if (centerVertex[piece_[h]] < 0) centerVertex[piece_[h]] = coarsest.handleVertex[h];
  }
  const double scale = base_.back().scale;
  pieceMap_.resize(coarsest.handles);
  for (int h = 0; h < coarsest.handles; ++h) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.block<3, 1>(0, 3) =
        (rest_[coarsest.handleVertex[h]] - rest_[centerVertex[piece_[h]]]) / scale;
    pieceMap_[h] = kron4x3(m.transpose(), Eigen::Matrix3d::Identity());
  }
}

Eigen::MatrixXd Multigrid::prolongationMatrix(int l) const {
  const MultigridLevel& level = levels_[l];
  if (l == 0) {
    Eigen::MatrixXd u = Eigen::MatrixXd::Zero(3 * level.parent.size(), 12 * level.handles);
    for (size_t r = 0; r < level.parent.size(); ++r) {
      if (level.parent[r] < 0) continue;
      for (int m = 0; m < 4; ++m) {
        u.block<3, 3>(3 * r, 12 * level.parent[r] + 3 * m) =
            level.y[r][m] * Eigen::Matrix3d::Identity();
      }
    }
    return u;
  }
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(12 * level.parent.size(), 12 * level.handles);
  for (size_t a = 0; a < level.parent.size(); ++a)
    u.block<12, 12>(12 * a, 12 * level.parent[a]) = level.toParent[a];
  return u;
}

}  // namespace galsculpt
