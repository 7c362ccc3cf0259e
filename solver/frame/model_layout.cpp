#include "solver/frame/model_layout.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace galsculpt {

namespace {

// Flattens groups into a CSR pair.
void flatten(const std::vector<std::vector<int>>& groups, std::vector<int>& start,
             std::vector<int>& items) {
  start.assign(1, 0);
  items.clear();
  for (const std::vector<int>& g : groups) {
    items.insert(items.end(), g.begin(), g.end());
    start.push_back(static_cast<int>(items.size()));
  }
}

}  // namespace

ModelLayout buildModelLayout(const SimModel& model) {
  ModelLayout m;
  m.vertices = model.numVertices();
  m.tets = model.numTets();
  m.edges = model.numEdges();
  m.blocks = static_cast<int>(model.pattern.columns.size());
  for (const Tet& t : model.mesh.tets)
    m.tetVertices.insert(m.tetVertices.end(), t.begin(), t.end());
  for (const auto& te : model.tetEdges) m.tetEdges.insert(m.tetEdges.end(), te.begin(), te.end());
  m.rest = model.rest;
  m.mass = model.mass;
  m.rowStart = model.pattern.rowStart;
  m.columns = model.pattern.columns;
  m.diagonal = model.pattern.diagonal;
  // Contributions in a fixed order: colour by colour, tets in colour order.
  std::vector<std::vector<int>> perVertex(m.vertices), perBlock(m.blocks);
  for (const std::vector<int>& color : model.colors) {
    for (int t : color) {
      for (int a = 0; a < 4; ++a) {
        perVertex[model.mesh.tets[t][a]].push_back(4 * t + a);
        for (int b = 0; b < 4; ++b)
          perBlock[model.scatter[t][4 * a + b]].push_back(16 * t + 4 * a + b);
      }
    }
  }
  flatten(perVertex, m.vertexSlotStart, m.vertexSlots);
  flatten(perBlock, m.blockSlotStart, m.blockSlots);
  return m;
}

FractureLayout buildFractureLayout(const FractureField& field) {
  FractureLayout f;
  f.slotStart = field.slotStart;
  f.slots = field.slots;
  f.threshold = field.threshold;
  for (const Vec3& p : field.midpoint) f.midpoint.insert(f.midpoint.end(), {p.x(), p.y(), p.z()});
  if (field.cells.empty()) return f;
  std::vector<std::pair<std::int64_t, std::pair<int, int>>> cells(field.cells.begin(),
                                                                  field.cells.end());
  std::sort(cells.begin(), cells.end());
  std::unordered_map<std::int64_t, int> index;
  for (const auto& [key, range] : cells) {
    index.emplace(key, f.cells());
    f.cellBegin.push_back(range.first);
    f.cellEnd.push_back(range.second);
  }
  f.cellEdges = field.cellEdges;
  f.edgeCell.assign(field.midpoint.size(), -1);
  f.cellNeighbors.assign(27 * static_cast<size_t>(f.cells()), -1);
  for (int c = 0; c < f.cells(); ++c) {
    const auto at = fractureCell(field.midpoint[f.cellEdges[f.cellBegin[c]]], field.cellSize);
    for (int i = f.cellBegin[c]; i < f.cellEnd[c]; ++i) f.edgeCell[f.cellEdges[i]] = c;
    int k = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz, ++k) {
          const auto it = index.find(fractureCellKey(at[0] + dx, at[1] + dy, at[2] + dz));
          if (it != index.end()) f.cellNeighbors[27 * c + k] = it->second;
        }
  }
  return f;
}

MultigridLayout buildMultigridLayout(const Multigrid& mg, const BlockPattern& fine) {
  MultigridLayout out;
  flatten(mg.fineColors(), out.fineColorStart, out.fineColorRows);
  for (int l = 0; l < mg.numLevels(); ++l) {
    const MultigridLevel& level = mg.level(l);
    LevelLayout ll;
    ll.rows = static_cast<int>(level.parent.size());
    ll.handles = level.handles;
    ll.parent = level.parent;
    if (l == 0) {
      for (const Eigen::Vector4d& y : level.y) ll.y.insert(ll.y.end(), y.data(), y.data() + 4);
    } else {
      for (const auto& t : level.toParent)
        ll.toParent.insert(ll.toParent.end(), t.data(), t.data() + 144);
    }
    ll.rowStart = level.rowStart;
    ll.columns = level.columns;
    ll.diagonal.assign(level.handles, -1);
    for (int h = 0; h < level.handles; ++h) {
      for (int k = level.rowStart[h]; k < level.rowStart[h + 1]; ++k)
        if (level.columns[k] == h) ll.diagonal[h] = k;
    }
    // The refresh's contributions in a fixed order: aggregate rows, then their blocks.
    const std::vector<int>& finerStart = l == 0 ? fine.rowStart : mg.level(l - 1).rowStart;
    const std::vector<int>& map = l == 0 ? level.fineToCoarseBlock : level.finerToCoarseBlock;
    std::vector<std::vector<int>> blocks(level.columns.size()), rowsOf(level.columns.size());
    for (int h = 0; h < level.handles; ++h) {
      for (int r : level.members[h]) {
        for (int k = finerStart[r]; k < finerStart[r + 1]; ++k) {
          if (map[k] < 0) continue;
          blocks[map[k]].push_back(k);
          rowsOf[map[k]].push_back(r);
        }
      }
    }
    flatten(blocks, ll.contribStart, ll.contribBlock);
    std::vector<int> unused;
    flatten(rowsOf, unused, ll.contribRow);
    flatten(level.members, ll.memberStart, ll.members);
    for (int h = 0; h < level.handles; ++h) ll.empty.push_back(level.members[h].empty() ? 1 : 0);
    flatten(level.colors, ll.colorStart, ll.colorRows);
    out.levels.push_back(std::move(ll));
  }
  out.pieceCount = mg.pieceCount();
  if (out.pieceCount >= 2) {
    const MultigridLevel& c = mg.level(mg.numLevels() - 1);
    out.pieceOfHandle = mg.pieceOfHandle();
    for (const auto& m : mg.pieceMaps())
      out.pieceMap.insert(out.pieceMap.end(), m.data(), m.data() + 144);
    std::vector<std::vector<int>> blocks(out.pieceCount), rows(out.pieceCount);
    for (int h = 0; h < c.handles; ++h) {
      for (int k = c.rowStart[h]; k < c.rowStart[h + 1]; ++k) {
        if (out.pieceOfHandle[c.columns[k]] != out.pieceOfHandle[h]) continue;
        blocks[out.pieceOfHandle[h]].push_back(k);
        rows[out.pieceOfHandle[h]].push_back(h);
      }
    }
    flatten(blocks, out.pieceContribStart, out.pieceContribBlock);
    std::vector<int> unused;
    flatten(rows, unused, out.pieceContribRow);
    std::vector<std::vector<int>> handlesOf(out.pieceCount);
    for (int h = 0; h < c.handles; ++h) handlesOf[out.pieceOfHandle[h]].push_back(h);
    flatten(handlesOf, out.pieceHandleStart, out.pieceHandles);
  }
  out.fragmentStart = mg.fragmentStart();
  out.fragmentVertices = mg.fragmentVertices();
  const int nVerts = static_cast<int>(mg.restPositions().size());
  out.fragmentOf.assign(nVerts, -1);
  const int fragments = static_cast<int>(out.fragmentStart.size()) - 1;
  for (int f = 0; f < fragments; ++f) {
    for (int i = out.fragmentStart[f]; i < out.fragmentStart[f + 1]; ++i)
      out.fragmentOf[out.fragmentVertices[i]] = f;
    const Vec3 c = mg.fragmentCenter(f);
    out.fragmentFrame.insert(out.fragmentFrame.end(), {c.x(), c.y(), c.z(), mg.fragmentScale(f)});
  }
  for (const Vec3& p : mg.restPositions())
    out.restPositions.insert(out.restPositions.end(), {p.x(), p.y(), p.z()});
  return out;
}

}  // namespace galsculpt
