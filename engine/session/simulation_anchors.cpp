// Simulation's tools and anchors: the knife's cuts, and anchors added, moved, released and
// removed (by the scene, scripts, brushes and anchor paint).
#include <algorithm>

#include "engine/session/simulation.h"

namespace galsculpt {

int Simulation::cut(const std::vector<BladeTriangle>& surface) {
  const int n = cutAlongSurface(model_, state_, surface);
  toolDamage_ += n;
  if (n > 0) updatePieces();  // volumes and exports see the new pieces before the next frame
  return n;
}

int Simulation::addAnchor(const std::vector<int>& vertices, const std::vector<AnchorKey>& path,
                          int releaseFrame, const std::string& name) {
  AnchorConstraint a;
  a.vertices = vertices;
  for (int v : vertices) a.origin.push_back(state_.x[v]);
  for (const AnchorKey& k : path) a.path.push_back({state_.time + k.time, k.offset});
  state_.anchors.push_back(std::move(a));
  anchorTags_.push_back({nextAnchorId_, releaseFrame, name});
  return nextAnchorId_++;
}

void Simulation::releaseAnchorsDue(int frame) {
  for (size_t i = 0; i < anchorTags_.size();) {
    const int release = anchorTags_[i].releaseFrame;
    if (release >= 0 && release <= frame) {
      anchorTags_.erase(anchorTags_.begin() + static_cast<long>(i));
      state_.anchors.erase(state_.anchors.begin() + static_cast<long>(i));
    } else {
      ++i;
    }
  }
}

std::optional<int> Simulation::namedAnchor(const std::string& name) const {
  for (auto t = anchorTags_.rbegin(); t != anchorTags_.rend(); ++t)
    if (!name.empty() && t->name == name) return t->id;
  return std::nullopt;
}

AnchorConstraint& Simulation::anchorWithId(int id) {
  for (size_t i = 0; i < anchorTags_.size(); ++i)
    if (anchorTags_[i].id == id) return state_.anchors[i];
  throw std::out_of_range("no anchor with id " + std::to_string(id));
}

void Simulation::setAnchorTargets(int id, const std::vector<Vec3>& targets) {
  AnchorConstraint& a = anchorWithId(id);
  if (targets.size() != a.vertices.size())
    throw std::invalid_argument("anchor targets: one per anchored vertex");
  a.origin = targets;
  a.path.clear();
}

void Simulation::setAnchorSprings(int id, const std::vector<double>& weights) {
  AnchorConstraint& a = anchorWithId(id);
  if (weights.size() != a.vertices.size())
    throw std::invalid_argument("anchor springs: one weight per anchored vertex");
  a.springWeights = weights;
}

int Simulation::unanchor(const std::vector<int>& vertices) {
  std::vector<char> drop(model_.numVertices(), 0);
  for (int v : vertices) drop[v] = 1;
  int dropped = 0;
  for (AnchorConstraint& a : state_.anchors) {
    size_t kept = 0;
    for (size_t i = 0; i < a.vertices.size(); ++i) {
      if (drop[a.vertices[i]]) {
        ++dropped;
        continue;
      }
      if (!a.origin.empty()) a.origin[kept] = a.origin[i];
      if (!a.springWeights.empty()) a.springWeights[kept] = a.springWeights[i];
      a.vertices[kept++] = a.vertices[i];
    }
    a.vertices.resize(kept);
    if (!a.origin.empty()) a.origin.resize(kept);
    if (!a.springWeights.empty()) a.springWeights.resize(kept);
  }
  return dropped;
}

std::vector<int> Simulation::anchoredVertices() const {
  std::vector<char> held(model_.numVertices(), 0);
  for (const AnchorConstraint& a : state_.anchors)
    for (int v : a.vertices) held[v] = 1;
  std::vector<int> out;
  for (int v = 0; v < model_.numVertices(); ++v)
    if (held[v]) out.push_back(v);
  return out;
}

void Simulation::removeAnchor(int id) {
  for (size_t i = 0; i < anchorTags_.size(); ++i) {
    if (anchorTags_[i].id != id) continue;
    anchorTags_.erase(anchorTags_.begin() + static_cast<long>(i));
    state_.anchors.erase(state_.anchors.begin() + static_cast<long>(i));
    return;
  }
  throw std::out_of_range("no anchor with id " + std::to_string(id));
}

}  // namespace galsculpt
