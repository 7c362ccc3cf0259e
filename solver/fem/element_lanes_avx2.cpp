// element_lanes_body.h for AVX2 (compiled with -mavx2, without FMA: see element_lanes.h).
#include "solver/fem/element_lanes.h"
#include "solver/fem/material_dispatch.h"

#define GALSCULPT_LANES_NAMESPACE avx2
#include "solver/fem/element_lanes_body.h"
// (After the intact elements' body: it uses its vector types and helpers.)
#include "solver/fem/cracked_lanes_body.h"
