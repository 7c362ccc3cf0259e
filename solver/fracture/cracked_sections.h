// Sections cracked through. Stress breaks edges one by one, but a part of the body can end up
// joined to the rest only through elements that are all cracked: two parts whose undamaged
// elements (tets with no damaged edge) share no face any more. What still links them are intact
// edges of cracked elements, which join them along a line or at a point: a section of no area,
// which the material could not hold in tension, and which no stress can break when the parts
// turn about it (a bent bar's last ligament on its compressed face becomes a pin: rotating the
// halves about it strains its edges only to second order, so the bar never parts).
//
// The rule: the parts are the face-connected sets of undamaged elements that each hold at least
// `fraction` of the body's rest volume (smaller sets, a lone sound tet in a crack, belong to
// whichever part reaches them). A vertex of a part's element belongs to that part (to the larger
// one where it touches two); any other vertex to the part nearest through intact edges
// (breadth first, in vertex order, so the result is the same on every executor and run). The
// intact edges whose vertices belong to different parts break. A cut or crack that leaves the
// undamaged elements face-connected around its front (a slit) breaks nothing; nor does a knife
// cut through (no intact edge crosses it). Damage only grows, so the rule never undoes a break.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/model/sim_model.h"

namespace galsculpt {

// The intact edges linking parts whose undamaged elements share no face, in increasing order;
// empty for fraction <= 0 or when the body holds fewer than two such parts. `neighbours`:
// tetFaceNeighbours(model.mesh), computed once (FractureField::tetNeighbours).
std::vector<int> crackedSectionEdges(const SimModel& model,
                                     const std::vector<std::array<int, 4>>& neighbours,
                                     const std::vector<std::uint8_t>& damaged, double fraction);

}  // namespace galsculpt
