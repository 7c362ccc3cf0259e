#include "solver/io/vtk_io.h"

#include <gtest/gtest.h>

#include <sstream>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(VtkIo, WritesPointsCellsTypesAndCellData) {
  test::TempDir dir;
  const TetMesh cube = test::unitCubeTets();
  std::vector<double> damage(cube.tets.size(), 0.0);
  damage[3] = 0.5;
  writeVtk(dir / "c.vtk", cube, {{"damage", damage}});
  std::istringstream in(test::readText(dir / "c.vtk"));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# vtk DataFile Version 3.0");
  const std::string text = test::readText(dir / "c.vtk");
  EXPECT_NE(text.find("POINTS 8 double"), std::string::npos);
  EXPECT_NE(text.find("CELLS 6 30"), std::string::npos);
  EXPECT_NE(text.find("CELL_TYPES 6\n10\n"), std::string::npos);
  EXPECT_NE(text.find("CELL_DATA 6\nSCALARS damage double 1\nLOOKUP_TABLE default\n0\n0\n0\n0.5\n"),
            std::string::npos);
}

TEST(VtkIo, RejectsBadFields) {
  test::TempDir dir;
  EXPECT_THROW_WITH(
      writeVtk(dir / "c.vtk", test::unitCubeTets(), {{"bad name", std::vector<double>(6)}}),
      OutputError, "without spaces");
  EXPECT_THROW_WITH(
      writeVtk(dir / "c.vtk", test::unitCubeTets(), {{"short", std::vector<double>(2)}}),
      OutputError, "one value per tet");
}

}  // namespace
}  // namespace galsculpt
