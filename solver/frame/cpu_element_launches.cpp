// The element launches (element_launches.h) for the CPU executor: the one translation unit of
// the CPU backend that includes a material model.
#include "solver/frame/element_launches.h"

#include "solver/frame/cpu_executor.h"

namespace galsculpt {

GALSCULPT_INSTANTIATE_ELEMENT_LAUNCHES(CpuExecutor);

}  // namespace galsculpt
