// Exact orientation test for the knife's segment-triangle tests.
//
// A floating-point determinant with a forward error bound decides almost every case; when the
// result is within the bound, the determinant is evaluated exactly with floating-point
// expansions (sums of non-overlapping doubles, after Shewchuk 1997): every difference and
// product is split into doubles whose sum is exact, and the sign of the total is read from its
// largest component. Valid for finite inputs away from overflow and underflow.
#pragma once

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// Sign of det[a-d; b-d; c-d]: +1 when d lies below the plane of (a, b, c) seen from the side
// where a, b, c are counter-clockwise (the same sign as tetSixVolume(d, a, b, c)), -1 above,
// 0 exactly on it.
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// The same determinant evaluated only in exact arithmetic (for tests of the filter).
int orient3dExact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

}  // namespace galsculpt
