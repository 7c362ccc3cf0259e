#include "engine/session/anchor_registry.h"

#include <algorithm>
#include <stdexcept>

namespace galsculpt {

int AnchorRegistry::add(const std::vector<int>& vertices, const std::vector<AnchorKey>& path,
                        int releaseFrame, const std::string& name) {
  AnchorConstraint a;
  a.vertices = vertices;
  for (int v : vertices) a.origin.push_back(state_.x[v]);
  for (const AnchorKey& k : path) a.path.push_back({state_.time + k.time, k.offset});
  state_.anchors.push_back(std::move(a));
  tags_.push_back({nextId_, releaseFrame, name});
  return nextId_++;
}

void AnchorRegistry::releaseDue(int frame) {
  for (size_t i = 0; i < tags_.size();) {
    const int release = tags_[i].releaseFrame;
    if (release >= 0 && release <= frame) {
      tags_.erase(tags_.begin() + static_cast<long>(i));
      state_.anchors.erase(state_.anchors.begin() + static_cast<long>(i));
      state_.letGo = true;
    } else {
      ++i;
    }
  }
}

std::optional<int> AnchorRegistry::named(const std::string& name) const {
  for (auto t = tags_.rbegin(); t != tags_.rend(); ++t)
    if (!name.empty() && t->name == name) return t->id;
  return std::nullopt;
}

AnchorConstraint& AnchorRegistry::withId(int id) {
  for (size_t i = 0; i < tags_.size(); ++i)
    if (tags_[i].id == id) return state_.anchors[i];
  throw std::out_of_range("no anchor with id " + std::to_string(id));
}

void AnchorRegistry::setTargets(int id, const std::vector<Vec3>& targets) {
  AnchorConstraint& a = withId(id);
  if (targets.size() != a.vertices.size())
    throw std::invalid_argument("anchor targets: one per anchored vertex");
  a.origin = targets;
  a.path.clear();
}

void AnchorRegistry::setSprings(int id, const std::vector<double>& weights) {
  AnchorConstraint& a = withId(id);
  if (weights.size() != a.vertices.size())
    throw std::invalid_argument("anchor springs: one weight per anchored vertex");
  a.springWeights = weights;
}

void AnchorRegistry::reshape(int id, std::vector<int> vertices, std::vector<Vec3> targets,
                             std::vector<double> weights) {
  AnchorConstraint& a = withId(id);
  if (targets.size() != vertices.size())
    throw std::invalid_argument("anchor targets: one per anchored vertex");
  if (!weights.empty() && weights.size() != vertices.size())
    throw std::invalid_argument("anchor springs: one weight per anchored vertex");
  a.vertices = std::move(vertices);
  a.origin = std::move(targets);
  a.springWeights = std::move(weights);
  a.path.clear();
}

int AnchorRegistry::unanchor(const std::vector<int>& vertices) {
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
  if (dropped > 0) state_.letGo = true;
  return dropped;
}

std::vector<int> AnchorRegistry::heldVertices() const {
  std::vector<char> held(model_.numVertices(), 0);
  for (const AnchorConstraint& a : state_.anchors)
    for (int v : a.vertices) held[v] = 1;
  std::vector<int> out;
  for (int v = 0; v < model_.numVertices(); ++v)
    if (held[v]) out.push_back(v);
  return out;
}

void AnchorRegistry::remove(int id) {
  for (size_t i = 0; i < tags_.size(); ++i) {
    if (tags_[i].id != id) continue;
    tags_.erase(tags_.begin() + static_cast<long>(i));
    state_.anchors.erase(state_.anchors.begin() + static_cast<long>(i));
    state_.letGo = true;
    return;
  }
  throw std::out_of_range("no anchor with id " + std::to_string(id));
}

void AnchorRegistry::addSceneAnchor(int index, AnchorConstraint anchor) {
  state_.anchors.push_back(std::move(anchor));
  tags_.push_back({-index - 1, -1, {}});
}

const AnchorConstraint* AnchorRegistry::find(int id) const {
  for (size_t i = 0; i < tags_.size(); ++i)
    if (tags_[i].id == id) return &state_.anchors[i];
  return nullptr;
}

void AnchorRegistry::restore(std::vector<AnchorTag> tags, int nextId) {
  tags_ = std::move(tags);
  nextId_ = nextId;
}

}  // namespace galsculpt
