// How far a tool that acted on nothing passed from the body: the words of the warning that says
// so (ToolApplier's reports, play's warnings).
#pragma once

#include <vector>

#include "solver/fracture/knife.h"

namespace galsculpt {

// The distance from `p` to the triangle (a, b, c).
double distanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// The least distance from any of `points` to the blade's surface.
double distanceToBlade(const std::vector<BladeTriangle>& blade, const std::vector<Vec3>& points);

}  // namespace galsculpt
