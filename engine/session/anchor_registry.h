// The anchors of a simulation as the session knows them: the solver reads each one's vertices,
// targets and springs from SimState::anchors; the registry keeps beside them what only the
// session needs (an id for each, the frame a script brush lets go, a script's name) and is the
// one place that adds, moves, releases and removes them (the scene, scripts, brushes, anchor
// paint). Whatever lets go of vertices (remove, releaseDue, unanchor) says so to the solver in
// SimState::letGo; adding, moving and reshaping an anchor (a stroke's rim) do not.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "solver/model/sim_model.h"

namespace galsculpt {

// What the session knows of each anchor of SimState::anchors besides what the solver reads.
struct AnchorTag {
  int id = 0;             // add's id; a scene's anchor i: -i - 1
  int releaseFrame = -1;  // the frame from which it lets go (a script brush's drag), -1: never
  std::string name;       // a script's named anchor ("anchor" events with "name"), or empty
  bool operator==(const AnchorTag&) const = default;
};

class AnchorRegistry {
 public:
  // The registry edits `state.anchors` (both must outlive it).
  AnchorRegistry(const SimModel& model, SimState& state) : model_(model), state_(state) {}

  // The scene's anchor `index` (its id: -index - 1).
  void addSceneAnchor(int index, AnchorConstraint anchor);
  // Holds `vertices` where they are now, moved by `path` offsets (times from now); returns an
  // id for remove. `releaseFrame` (>= 0): releaseDue lets it go from that frame on. `name`:
  // found by named. Both are part of the state (snapshots, projects): after an undo or in a
  // reopened project a brush lets go and a name is found as before.
  int add(const std::vector<int>& vertices, const std::vector<AnchorKey>& path = {},
          int releaseFrame = -1, const std::string& name = {});
  // Removes the anchors whose release frame is at or before `frame`.
  void releaseDue(int frame);
  // The id of the latest anchor named `name` still holding (names stack as a script's adds and
  // removes do), or nullopt.
  std::optional<int> named(const std::string& name) const;
  // Moves an anchor's vertices to `targets` (same order as its vertices) from the next frame
  // on: brushes drag what they hold this way. Throws std::out_of_range for an unknown id.
  void setTargets(int id, const std::vector<Vec3>& targets);
  // Makes an anchor soft: each vertex pulled toward its target by a spring of weight `weights[i]`
  // in [0, 1] (AnchorConstraint::springWeights) instead of held there. Throws std::out_of_range
  // for an unknown id, std::invalid_argument unless one weight per vertex.
  void setSprings(int id, const std::vector<double>& weights);
  // A brush's hold from the next frame on: the anchor keeps its id and its place among the
  // anchors, and holds `vertices` pulled toward `targets` by springs of `weights` (one each;
  // empty weights: held exactly), without a path. Throws as setTargets and setSprings do.
  void reshape(int id, std::vector<int> vertices, std::vector<Vec3> targets,
               std::vector<double> weights);
  // Frees the given vertices from every anchor (scene, script and painted ones alike);
  // returns how many anchor entries were dropped.
  int unanchor(const std::vector<int>& vertices);
  // Every vertex some anchor holds, ascending.
  std::vector<int> heldVertices() const;
  // Removes an anchor added by add or, with id < 0, the scene's anchor -id - 1. Throws
  // std::out_of_range for an unknown id.
  void remove(int id);
  // The anchor with this id, or null (removed).
  const AnchorConstraint* find(int id) const;

  // For snapshots: the tags (one per SimState::anchors entry) and the next id; restore puts
  // back both, with the state's anchors restored by the caller.
  const std::vector<AnchorTag>& tags() const { return tags_; }
  int nextId() const { return nextId_; }
  void restore(std::vector<AnchorTag> tags, int nextId);

 private:
  AnchorConstraint& withId(int id);  // throws std::out_of_range for an unknown id
  const SimModel& model_;
  SimState& state_;
  std::vector<AnchorTag> tags_;  // one per entry of state_.anchors
  int nextId_ = 0;
};

}  // namespace galsculpt
