#include "solver/fem/colliders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace galsculpt {
namespace {

TEST(Colliders, PlaneSphereAndBoxDistances) {
  Collider plane;
  plane.point = Vec3(0, -1, 0);
  EXPECT_NEAR(colliderDistance(plane, Vec3(3, -1.5, 2), 0).distance, -0.5, 1e-15);
  Collider sphere;
  sphere.type = Collider::Type::Sphere;
  sphere.center = Vec3(1, 0, 0);
  sphere.radius = 0.5;
  const ContactSample s = colliderDistance(sphere, Vec3(1, 0.25, 0), 0);
  EXPECT_NEAR(s.distance, -0.25, 1e-15);
  EXPECT_TRUE(s.normal.isApprox(Vec3::UnitY()));
  Collider box;
  box.type = Collider::Type::Box;
  box.halfExtents = Vec3(1, 2, 3);
  EXPECT_NEAR(colliderDistance(box, Vec3(0.9, 0, 0), 0).distance, -0.1, 1e-12);
  EXPECT_TRUE(colliderDistance(box, Vec3(0.9, 0, 0), 0).normal.isApprox(Vec3::UnitX()));
  EXPECT_NEAR(colliderDistance(box, Vec3(4, 5, 3), 0).distance, std::hypot(3.0, 3.0), 1e-12);
}

// A box with rounded edges: the inner box grown by the radius. Its faces are where the sharp
// box's are, its edges quarter cylinders, and the same box with radius 0 is the sharp one.
TEST(Colliders, ARoundedBoxIsItsInnerBoxGrownByTheRadius) {
  Collider box;
  box.type = Collider::Type::Box;
  box.halfExtents = Vec3(1, 2, 3);
  box.cornerRadius = 0.25;
  // On a face's middle: as the sharp box.
  EXPECT_NEAR(colliderDistance(box, Vec3(0.9, 0, 0), 0).distance, -0.1, 1e-12);
  EXPECT_NEAR(colliderDistance(box, Vec3(0, 2.5, 0), 0).distance, 0.5, 1e-12);
  // Off the edge x = 1, y = 2: the distance to the edge's axis (0.75, 1.75) less the radius.
  const Vec3 out(1.1, 2.1, 0);
  EXPECT_NEAR(colliderDistance(box, out, 0).distance, std::hypot(0.35, 0.35) - 0.25, 1e-12);
  EXPECT_TRUE(colliderDistance(box, out, 0).normal.isApprox(Vec3(1, 1, 0).normalized()));
  // Inside near that edge, less than the radius deep: in the rounded zone, normal radial.
  const Vec3 in(0.9, 1.9, 0);
  EXPECT_NEAR(colliderDistance(box, in, 0).distance, std::hypot(0.15, 0.15) - 0.25, 1e-12);
  EXPECT_TRUE(colliderDistance(box, in, 0).normal.isApprox(Vec3(1, 1, 0).normalized()));
  // Deeper than the radius: out through the nearest face.
  EXPECT_NEAR(colliderDistance(box, Vec3(0.5, 0, 0), 0).distance, -0.5, 1e-12);
  EXPECT_TRUE(colliderDistance(box, Vec3(0.5, 0, 0), 0).normal.isApprox(Vec3::UnitX()));
  // A corner is a sphere of the radius round the inner box's corner.
  EXPECT_NEAR(colliderDistance(box, Vec3(1, 2, 3), 0).distance, std::sqrt(3.0) * 0.25 - 0.25,
              1e-12);
}

// The contact force k (-phi) n is the gradient of the penalty 1/2 k phi^2 only where n is the
// gradient of phi, and Newton settles a vertex on a collider only where that force is
// continuous. Round a sharp box's edge the normal flips from one face's to the other's; round a
// rounded box's edge, less than the radius deep, it turns smoothly and is phi's gradient.
TEST(Colliders, ARoundedBoxesNormalIsTheDistancesGradientAndTurnsSmoothlyRoundAnEdge) {
  Collider rounded;
  rounded.type = Collider::Type::Box;
  rounded.halfExtents = Vec3(1, 2, 3);
  rounded.cornerRadius = 0.25;
  Collider sharp = rounded;
  sharp.cornerRadius = 0.0;
  // A path a tenth of the radius deep round the edge x = 1, y = 2 (its axis at (0.75, 1.75)).
  const double depth = 0.025, radius = rounded.cornerRadius - depth;
  double roundedJump = 0.0, sharpJump = 0.0;
  Vec3 lastRounded = Vec3::Zero(), lastSharp = Vec3::Zero();
  const int steps = 200;
  for (int i = 0; i <= steps; ++i) {
    const double a = 0.5 * M_PI * i / steps;
    const Vec3 p(0.75 + radius * std::cos(a), 1.75 + radius * std::sin(a), 0.3);
    const ContactSample r = colliderDistance(rounded, p, 0);
    const ContactSample s = colliderDistance(sharp, p, 0);
    EXPECT_NEAR(r.distance, -depth, 1e-12);
    if (i > 0) {
      roundedJump = std::max(roundedJump, (r.normal - lastRounded).norm());
      sharpJump = std::max(sharpJump, (s.normal - lastSharp).norm());
    }
    lastRounded = r.normal;
    lastSharp = s.normal;
    // Central differences of phi give the normal.
    const double e = 1e-7;
    Vec3 g;
    for (int k = 0; k < 3; ++k) {
      const Vec3 dp = Vec3::Unit(k) * e;
      g[k] = (colliderDistance(rounded, p + dp, 0).distance -
              colliderDistance(rounded, p - dp, 0).distance) /
             (2 * e);
    }
    EXPECT_LT((g - r.normal).norm(), 1e-6) << "at angle " << a;
  }
  EXPECT_LT(roundedJump, 2.0 * 0.5 * M_PI / steps) << "the normal turns with the path";
  EXPECT_GT(sharpJump, 1.0) << "the sharp box's normal flips at the diagonal";
}

TEST(Colliders, LinearAndPendulumMotion) {
  Collider moving;
  moving.type = Collider::Type::Sphere;
  moving.radius = 1;
  moving.motion.type = ColliderMotion::Type::Linear;
  moving.motion.velocity = Vec3(2, 0, 0);
  EXPECT_NEAR(colliderDistance(moving, Vec3(4, 0, 0), 1.0).distance, 1.0, 1e-12);

  // A hammer hanging 1 m below its pivot, swinging about x at 2 rad/s: after pi/4 s it has
  // turned 90 degrees, from straight down to pointing along +y... no: along -z... check by pose.
  Collider hammer;
  hammer.type = Collider::Type::Sphere;
  hammer.radius = 0.1;
  hammer.center = Vec3(0, 0, -1);
  hammer.motion.type = ColliderMotion::Type::Pendulum;
  hammer.motion.pivot = Vec3::Zero();
  hammer.motion.axis = Vec3::UnitX();
  hammer.motion.angularVelocity = 2.0;
  const double t = M_PI / 4;
  const Vec3 centre = colliderRotation(hammer, t) * hammer.center + colliderTranslation(hammer, t);
  EXPECT_NEAR((centre - Vec3(0, 1, 0)).norm(), 0.0, 1e-12)
      << "omega x r at the bottom points along +y";
  EXPECT_NEAR(colliderDistance(hammer, Vec3(0, 1, 0), t).distance, -0.1, 1e-12);
}

// A rigid pendulum left to swing from 0.2 rad keeps its energy (semi-implicit Euler: bounded,
// no drift) and swings with the period of a simple pendulum of its length.
TEST(Colliders, ARigidPendulumSwingsWithItsPeriodAndKeepsItsEnergy) {
  Collider bob;
  bob.type = Collider::Type::Sphere;
  bob.radius = 0.05;
  bob.center = Vec3(0, 0, 0);
  bob.motion.type = ColliderMotion::Type::Pendulum;
  bob.motion.pivot = Vec3(0, 0, 1);
  bob.motion.axis = Vec3::UnitX();
  bob.motion.mass = 2.0;
  const Vec3 g(0, 0, -9.81);
  ColliderState s;
  s.angle = 0.2;
  const double e0 = pendulumEnergy(bob, s, g);
  EXPECT_NEAR(e0, 2.0 * 9.81 * (1.0 - std::cos(0.2)), 1e-12);
  EXPECT_NEAR(pendulumGravityMoment(bob, 0.2, g), -2.0 * 9.81 * std::sin(0.2), 1e-12);
  const double h = 1e-3;
  double drift = 0.0, lastCrossing = -1.0, period = 0.0;
  for (int i = 1; i <= 4000; ++i) {
    const double before = s.angle;
    advancePendulum(bob, s, h, 0.0, g);
    drift = std::max(drift, std::abs(pendulumEnergy(bob, s, g) - e0) / e0);
    if (before > 0.0 && s.angle <= 0.0) {  // downward crossings, one a period
      const double t = h * (i - 1 + before / (before - s.angle));
      if (lastCrossing >= 0.0) period = t - lastCrossing;
      lastCrossing = t;
    }
  }
  // T = 2 pi sqrt(L / g) (1 + theta0^2 / 16 + ...)
  EXPECT_NEAR(period, 2.0 * M_PI * std::sqrt(1.0 / 9.81) * (1.0 + 0.04 / 16.0), 2e-3);
  EXPECT_LT(drift, 2e-3);
  // Moved by a contact moment: the angular impulse is I dw.
  ColliderState pushed;
  advancePendulum(bob, pushed, h, 3.0, Vec3::Zero());
  EXPECT_NEAR(pushed.angularVelocity * pendulumInertia(bob), 3.0 * h, 1e-15);
}

}  // namespace
}  // namespace galsculpt
