#include "solver/io/vtk_io.h"

#include <iomanip>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

void writeVtk(const std::filesystem::path& path, const TetMesh& mesh,
              const std::vector<VtkCellField>& cellFields) {
  for (const VtkCellField& f : cellFields) {
    if (f.values.size() != mesh.tets.size() || f.name.empty() ||
        f.name.find_first_of(" \t\n") != std::string::npos) {
      throw OutputError("cannot write " + path.string() + ": cell field '" + f.name +
                        "' needs a name without spaces and one value per tet");
    }
  }
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "# vtk DataFile Version 3.0\ngalsculpt tet mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    out << std::setprecision(17);
    out << "POINTS " << mesh.numVertices() << " double\n";
    for (const Vec3& p : mesh.vertices) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    out << "CELLS " << mesh.numTets() << ' ' << 5 * mesh.numTets() << '\n';
    for (const Tet& t : mesh.tets)
      out << "4 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
    out << "CELL_TYPES " << mesh.numTets() << '\n';
    for (int i = 0; i < mesh.numTets(); ++i) out << "10\n";
    if (!cellFields.empty()) {
      out << "CELL_DATA " << mesh.numTets() << '\n';
      for (const VtkCellField& f : cellFields) {
        out << "SCALARS " << f.name << " double 1\nLOOKUP_TABLE default\n";
        for (double v : f.values) out << v << '\n';
      }
    }
  });
}

}  // namespace galsculpt
