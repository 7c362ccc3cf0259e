// The damage a frame solves under: the host copy beside the executor's (FrameData::damaged),
// the state's revision it came with, and a count of its changes by content, which what the host
// derives from the damage is keyed on (the pieces, piece_tracker.h, and the removed debris).
// A state's revision alone cannot key them: a backend may be handed several states under one
// revision (tests, undo snapshots), so their damage is compared by content.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fracture/cracked_sections.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/piece_tracker.h"
#include "solver/frame/step.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
class FrameDamage {
 public:
  FrameDamage(const SimModel& model, FrameData<Exec>& data) : model_(model), d_(data) {}

  // Takes the state's damage where its revision or content differs; whether it did.
  bool syncIn(const SimState& state) {
    const bool contentChanged = host_ != state.damaged;
    if (state.damageRevision == revision_ && !contentChanged) return false;
    if (contentChanged) ++changes_;
    host_ = state.damaged;
    d_.damaged.upload(host_);
    revision_ = state.damageRevision;
    return true;
  }

  void syncOut(SimState& state) const {
    if (revision_ == state.damageRevision) return;
    state.damaged = host_;
    state.damageRevision = revision_;
  }

  // After the fracture pass marked edges broken in the executor's copy: the host's follows, and
  // the sections a crack has parted (cracked_sections.h) break whole. Returns how many edges
  // the parting added.
  int takeBreaks() {
    d_.damaged.download(host_.data(), host_.size());
    const std::vector<int> parted = crackedSectionEdges(
        model_, model_.fracture.tetNeighbours, host_, model_.fracture.settings.partingFraction);
    if (!parted.empty()) {
      for (const int e : parted) host_[e] = 1;
      d_.damaged.upload(host_);
    }
    ++revision_;
    ++changes_;
    return static_cast<int>(parted.size());
  }

  const std::vector<std::uint8_t>& host() const { return host_; }
  std::uint64_t revision() const { return revision_; }
  std::uint64_t changes() const { return changes_; }  // of the content
  const PieceCensus& census() { return tracker_.census(model_, host_, changes_); }
  const PieceLayout& pieces() { return tracker_.layout(model_, host_, changes_); }

 private:
  const SimModel& model_;
  FrameData<Exec>& d_;
  PieceTracker tracker_;
  std::vector<std::uint8_t> host_;
  std::uint64_t revision_ = ~std::uint64_t{0};
  std::uint64_t changes_ = 0;
};

}  // namespace galsculpt
