#include "engine/session/anchor_registry.h"

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace galsculpt {
namespace {

struct Bar {
  SimModel model = buildSimModel(test::gridBar(3, 1, 1, 0.1), MaterialParams{});
  SimState state = initialState(model);
  AnchorRegistry anchors{model, state};
};

// Ids count up from 0 for added anchors and -i - 1 for the scene's; each entry of the state's
// anchors keeps its tag beside it, whatever is removed in between.
TEST(AnchorRegistry, IdsFollowTheirAnchorsThroughRemovals) {
  Bar b;
  b.anchors.addSceneAnchor(0, AnchorConstraint{{0, 1}, {}, {b.state.x[0], b.state.x[1]}, {}});
  const int first = b.anchors.add({2});
  const int second = b.anchors.add({3, 4}, {}, -1, "grip");
  EXPECT_EQ(first, 0);
  EXPECT_EQ(second, 1);
  ASSERT_EQ(b.state.anchors.size(), 3u);
  EXPECT_EQ(b.state.anchors[2].origin[1], b.state.x[4]) << "held where it is now";
  b.anchors.remove(first);
  ASSERT_NE(b.anchors.find(second), nullptr);
  EXPECT_EQ(b.anchors.find(second)->vertices, (std::vector<int>{3, 4}));
  EXPECT_EQ(b.anchors.find(first), nullptr);
  EXPECT_EQ(b.anchors.find(-1)->vertices, (std::vector<int>{0, 1}));
  b.anchors.remove(-1);
  EXPECT_EQ(b.state.anchors.size(), 1u);
  EXPECT_EQ(b.anchors.tags().size(), 1u);
  EXPECT_THROW(b.anchors.remove(first), std::out_of_range);
  EXPECT_EQ(b.anchors.add({5}), 2) << "ids are never reused";
}

TEST(AnchorRegistry, NamesStackAndReleaseFramesLetGo) {
  Bar b;
  const int a = b.anchors.add({0}, {}, -1, "grip");
  const int c = b.anchors.add({1}, {}, -1, "grip");
  b.anchors.add({2}, {}, 5);
  EXPECT_EQ(b.anchors.named("grip"), c) << "the latest of the name";
  b.anchors.remove(c);
  EXPECT_EQ(b.anchors.named("grip"), a);
  EXPECT_FALSE(b.anchors.named("other"));
  EXPECT_FALSE(b.anchors.named("")) << "an empty name finds nothing";
  b.anchors.releaseDue(4);
  EXPECT_EQ(b.state.anchors.size(), 2u);
  b.anchors.releaseDue(5);
  EXPECT_EQ(b.state.anchors.size(), 1u);
  EXPECT_EQ(b.anchors.heldVertices(), (std::vector<int>{0}));
}

TEST(AnchorRegistry, TargetsAndSpringsAreCheckedAndPaintCanBeErased) {
  Bar b;
  const int id = b.anchors.add({0, 1, 2}, {{0.0, Vec3::Zero()}, {1.0, Vec3::UnitX()}});
  EXPECT_EQ(b.state.anchors[0].path.size(), 2u);
  const std::vector<Vec3> targets{Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)};
  b.anchors.setTargets(id, targets);
  EXPECT_EQ(b.state.anchors[0].origin, targets);
  EXPECT_TRUE(b.state.anchors[0].path.empty()) << "a brush's targets replace the path";
  EXPECT_THROW(b.anchors.setTargets(id, {Vec3::Zero()}), std::invalid_argument);
  EXPECT_THROW(b.anchors.setTargets(7, targets), std::out_of_range);
  EXPECT_THROW(b.anchors.setSprings(id, {0.5}), std::invalid_argument);
  b.anchors.setSprings(id, {0.1, 0.2, 0.3});
  b.anchors.add({1, 3});
  EXPECT_EQ(b.anchors.heldVertices(), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(b.anchors.unanchor({1}), 2) << "both anchors' entries of vertex 1";
  EXPECT_EQ(b.state.anchors[0].vertices, (std::vector<int>{0, 2}));
  EXPECT_EQ(b.state.anchors[0].origin, (std::vector<Vec3>{targets[0], targets[2]}));
  EXPECT_EQ(b.state.anchors[0].springWeights, (std::vector<double>{0.1, 0.3}));
}

// What lets go of vertices (a removal, a due release, an unanchor that dropped some) says so to
// the solver (SimState::letGo); adding, moving, reshaping (a stroke's rim) and softening do not.
TEST(AnchorRegistry, WhatLetsGoOfVerticesSaysSoToTheSolver) {
  Bar b;
  const int grip = b.anchors.add({0, 1});
  const int brush = b.anchors.add({2, 3}, {}, 4);
  b.anchors.setTargets(grip, {Vec3(0, 0, 0), Vec3(1, 0, 0)});
  b.anchors.setSprings(grip, {0.5, 0.5});
  b.anchors.reshape(brush, {2}, {Vec3(2, 0, 0)}, {1.0});
  EXPECT_EQ(b.anchors.unanchor({5}), 0);
  b.anchors.releaseDue(3);
  EXPECT_FALSE(b.state.letGo) << "nothing let go";
  b.anchors.releaseDue(4);
  EXPECT_TRUE(b.state.letGo) << "a due release";
  b.state.letGo = false;
  EXPECT_EQ(b.anchors.unanchor({1}), 1);
  EXPECT_TRUE(b.state.letGo) << "an unanchor";
  b.state.letGo = false;
  b.anchors.remove(grip);
  EXPECT_TRUE(b.state.letGo) << "a removal (a stroke's end)";
}

TEST(AnchorRegistry, RestoreBringsBackTagsAndTheNextId) {
  Bar b;
  b.anchors.add({0}, {}, 3, "a");
  const std::vector<AnchorTag> tags = b.anchors.tags();
  const std::vector<AnchorConstraint> anchors = b.state.anchors;
  b.anchors.add({1});
  b.state.anchors = anchors;
  b.anchors.restore(tags, 1);
  EXPECT_EQ(b.anchors.tags(), tags);
  EXPECT_EQ(b.anchors.named("a"), 0);
  EXPECT_EQ(b.anchors.add({2}), 1);
}

// A brush's anchor is reshaped in place each frame: its id and place among the anchors stay.
TEST(AnchorRegistry, ReshapeKeepsTheIdAndThePlace) {
  Bar b;
  const int brush = b.anchors.add({0, 1}, {{0.0, Vec3::Zero()}, {1.0, Vec3::UnitX()}});
  const int grip = b.anchors.add({5});
  b.anchors.reshape(brush, {2, 3, 4}, {Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)},
                    {1.0, 0.5, 0.1});
  ASSERT_EQ(b.state.anchors.size(), 2u);
  const AnchorConstraint& a = b.state.anchors[0];
  EXPECT_EQ(a.vertices, (std::vector<int>{2, 3, 4}));
  EXPECT_EQ(a.origin[2], Vec3(3, 0, 0));
  EXPECT_EQ(a.springWeights, (std::vector<double>{1.0, 0.5, 0.1}));
  EXPECT_TRUE(a.path.empty());
  EXPECT_EQ(b.anchors.find(grip)->vertices, (std::vector<int>{5}));
  EXPECT_EQ(b.anchors.nextId(), 2);
  EXPECT_THROW(b.anchors.reshape(brush, {1}, {}, {}), std::invalid_argument);
  EXPECT_THROW(b.anchors.reshape(brush, {1}, {Vec3::Zero()}, {0.5, 0.5}), std::invalid_argument);
  EXPECT_THROW(b.anchors.reshape(9, {1}, {Vec3::Zero()}, {}), std::out_of_range);
  b.anchors.reshape(brush, {1}, {Vec3::Zero()}, {});
  EXPECT_TRUE(b.state.anchors[0].springWeights.empty()) << "held exactly";
}

}  // namespace
}  // namespace galsculpt
