// element_lanes_body.h for any x86-64 (SSE2: the compiler splits each four-double operation in
// two).
#include "solver/fem/element_lanes.h"
#include "solver/fem/material_dispatch.h"

#define GALSCULPT_LANES_NAMESPACE portable
#include "solver/fem/element_lanes_body.h"
// (After the intact elements' body: it uses its vector types and helpers.)
#include "solver/fem/cracked_lanes_body.h"
