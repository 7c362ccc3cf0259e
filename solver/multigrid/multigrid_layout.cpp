#include "solver/multigrid/multigrid_layout.h"

#include "solver/mesh/csr.h"

namespace galsculpt {

MultigridLayout buildMultigridLayout(const Multigrid& mg, const BlockPattern& fine) {
  MultigridLayout out;
  flattenGroups(mg.fineColors(), out.fineColorStart, out.fineColorRows);
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
    flattenGroups(blocks, ll.contribStart, ll.contribBlock);
    std::vector<int> unused;
    flattenGroups(rowsOf, unused, ll.contribRow);
    flattenGroups(level.members, ll.memberStart, ll.members);
    for (int h = 0; h < level.handles; ++h) ll.empty.push_back(level.members[h].empty() ? 1 : 0);
    flattenGroups(level.colors, ll.colorStart, ll.colorRows);
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
    flattenGroups(blocks, out.pieceContribStart, out.pieceContribBlock);
    std::vector<int> unused;
    flattenGroups(rows, unused, out.pieceContribRow);
    std::vector<std::vector<int>> handlesOf(out.pieceCount);
    for (int h = 0; h < c.handles; ++h) handlesOf[out.pieceOfHandle[h]].push_back(h);
    flattenGroups(handlesOf, out.pieceHandleStart, out.pieceHandles);
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
