// Deterministic closed surfaces for the paper's scenes; tetrahedralized by TetGen (engine/).
//
// All lengths in metres. Same arguments, same surface, on every machine: noise comes from a
// fixed-seed std::mt19937 whose raw output is mapped by hand (the standard distributions are
// not reproducible across library implementations).
#pragma once

#include <cstdint>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// Subdivided icosahedron projected on the sphere: 20 * 4^subdivisions faces.
TriMesh makeIcosphere(double radius, int subdivisions);

// Standard Charpy specimen: 55 x 10 x 10 mm bar along x, with a 2 mm deep 45-degree V-notch
// in the middle of the top face (y = 10 mm). Origin at the bar's lower corner.
TriMesh makeCharpyBar();

// A steak-like slab about 200 x 30 x 120 mm with an irregular, lumpy outline and uneven
// thickness, centred at the origin (thin along y). Built as rings around the y axis from the
// top pole over the rounded rim to the bottom pole, spaced by `edgeLength` (m) along the
// surface, so that triangles are close to equilateral (TetGen would refine slivers).
TriMesh makeSteakSlab(double edgeLength = 0.002, std::uint32_t seed = 186);

}  // namespace galsculpt
