// Legacy VTK (ASCII unstructured grid) output for ParaView, with optional per-cell fields
// (damage, stress, piece). Output only: VTK is a viewing format here, not an input.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct VtkCellField {
  std::string name;            // no spaces
  std::vector<double> values;  // (nTets)
};

void writeVtk(const std::filesystem::path& path, const TetMesh& mesh,
              const std::vector<VtkCellField>& cellFields = {});

}  // namespace galsculpt
