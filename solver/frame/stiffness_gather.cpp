#include "solver/frame/stiffness_gather.h"

#include <algorithm>

#include "solver/frame/parallel.h"

namespace galsculpt {

StiffnessGather::StiffnessGather(const BlockPattern& pattern,
                                 const std::vector<TetScatter>& scatter, const int* tetVertices)
    : pattern_(pattern), tetVertices_(tetVertices), tets_(static_cast<int>(scatter.size())) {
  target_.resize(static_cast<size_t>(ElementPass::kPackedBlocks) * tets_);
  for (int t = 0; t < tets_; ++t)
    for (int a = 0; a < 4; ++a)
      for (int c = a; c < 4; ++c) {
        // Block (a, c) of the element lies above the diagonal where its corners are in order;
        // otherwise its transpose is block (c, a), which does.
        const int b = tetVertices[4 * t + a] <= tetVertices[4 * t + c] ? scatter[t][4 * a + c]
                                                                       : scatter[t][4 * c + a];
        target_[ElementPass::kPackedBlocks * static_cast<size_t>(t) +
                ElementPass::packedBlock(a, c)] = b;
      }
  dirty_.resize(pattern.columns.size());
}

int StiffnessGather::rangesFor(int threads, int rows) {
  return std::max(1, std::min(rows, 4 * threads));
}

void StiffnessGather::buildRanges(int ranges) {
  ranges_ = ranges;
  const int rows = pattern_.rows;
  rangeRow_.resize(ranges + 1);
  for (int p = 0; p <= ranges; ++p)
    rangeRow_[p] = static_cast<int>(static_cast<long>(rows) * p / ranges);
  std::vector<int> rangeOfRow(rows);
  for (int p = 0; p < ranges; ++p)
    for (int r = rangeRow_[p]; r < rangeRow_[p + 1]; ++r) rangeOfRow[r] = p;
  std::vector<std::vector<int>> lists(ranges);
  for (int t = 0; t < tets_; ++t) {
    const int* corner = tetVertices_ + 4 * static_cast<size_t>(t);
    for (int a = 0; a < 4; ++a) {  // the rows of its blocks: its corners
      std::vector<int>& list = lists[rangeOfRow[corner[a]]];
      if (list.empty() || list.back() != t) list.push_back(t);
    }
  }
  rangeTetStart_.assign(1, 0);
  rangeTets_.clear();
  for (const std::vector<int>& list : lists) {
    rangeTets_.insert(rangeTets_.end(), list.begin(), list.end());
    rangeTetStart_.push_back(static_cast<int>(rangeTets_.size()));
  }
}

void StiffnessGather::gatherUpper(const double* packed, const std::uint8_t* opened,
                                  const std::uint8_t* fresh, const std::uint8_t* touched,
                                  double* kb) {
  const int ranges = rangesFor(threadCount(), pattern_.rows);
  if (ranges != ranges_) buildRanges(ranges);
  const long work = static_cast<long>(rangeTets_.size()) / std::max(1, ranges) * 100;
  parallelFor(
      ranges,
      [&](int p) {
        const int r0 = rangeRow_[p], r1 = rangeRow_[p + 1];
        const int b0 = pattern_.rowStart[r0], b1 = pattern_.rowStart[r1];
        const int* tets = rangeTets_.data() + rangeTetStart_[p];
        const int count = rangeTetStart_[p + 1] - rangeTetStart_[p];
        std::uint8_t* dirty = dirty_.data();
        const bool all = !fresh && !touched;
        for (int b = b0; b < b1; ++b) dirty[b] = all;
        if (!all) {
          for (int i = 0; i < count; ++i) {
            const int t = tets[i];
            if (fresh && !fresh[t]) continue;
            const int* target =
                target_.data() + ElementPass::kPackedBlocks * static_cast<size_t>(t);
            const int* corner = tetVertices_ + 4 * static_cast<size_t>(t);
            for (int a = 0; a < 4; ++a)
              for (int c = a; c < 4; ++c) {
                const int b = target[ElementPass::packedBlock(a, c)];
                if (b < b0 || b >= b1) continue;
                if (touched && !(touched[corner[a]] && touched[corner[c]])) continue;
                dirty[b] = 1;
              }
          }
        }
        for (int r = r0; r < r1; ++r)  // the blocks on and above the diagonal
          for (int b = pattern_.rowStart[r]; b < pattern_.rowStart[r + 1]; ++b)
            if (dirty[b] && pattern_.columns[b] >= r)
              for (int i = 0; i < 9; ++i) kb[9 * static_cast<size_t>(b) + i] = 0.0;
        for (int i = 0; i < count; ++i) {
          const int t = tets[i];
          if (ElementPass::zeroStiffness(opened[t])) continue;
          const int* target = target_.data() + ElementPass::kPackedBlocks * static_cast<size_t>(t);
          const int* corner = tetVertices_ + 4 * static_cast<size_t>(t);
          const double* h = packed + ElementPass::kPackedHessian * static_cast<size_t>(t);
          for (int a = 0; a < 4; ++a)
            for (int c = a; c < 4; ++c) {
              const int k = ElementPass::packedBlock(a, c), b = target[k];
              if (b < b0 || b >= b1 || !dirty[b]) continue;
              const double* blk = h + 9 * k;
              double* out = kb + 9 * static_cast<size_t>(b);
              if (corner[a] <= corner[c]) {
                for (int e = 0; e < 9; ++e) out[e] += blk[e];
              } else {  // the element's block (c, a) is the transpose of its packed (a, c)
                for (int j = 0; j < 3; ++j)
                  for (int r = 0; r < 3; ++r) out[r + 3 * j] += blk[j + 3 * r];
              }
            }
        }
      },
      work);
}

}  // namespace galsculpt
