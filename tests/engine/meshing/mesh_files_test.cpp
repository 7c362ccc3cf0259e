#include "engine/meshing/mesh_files.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(MeshFiles, KindFromExtension) {
  EXPECT_EQ(meshFileKind("a.node"), MeshFileKind::TetGen);
  EXPECT_EQ(meshFileKind("a.ELE"), MeshFileKind::TetGen);
  EXPECT_EQ(meshFileKind("a.msh"), MeshFileKind::Gmsh);
  EXPECT_EQ(meshFileKind("a.vtk"), MeshFileKind::Vtk);
  EXPECT_EQ(meshFileKind("a.Stl"), MeshFileKind::Surface);
  EXPECT_EQ(meshFileKind("a.glb"), MeshFileKind::Surface);
  EXPECT_EQ(meshFileKind("a.doc"), MeshFileKind::Unknown);
}

TEST(MeshFiles, TetFormatsRoundTrip) {
  test::TempDir dir;
  const TetMesh cube = test::unitCubeTets(0.5);
  for (const char* name : {"c.node", "c.msh"}) {
    writeTetMesh(dir / name, cube);
    const TetMesh back = readTetMesh(dir / name);
    EXPECT_EQ(back.vertices, cube.vertices) << name;
    EXPECT_EQ(back.tets, cube.tets) << name;
  }
  std::vector<double> damage(6, 0.25);
  writeTetMesh(dir / "d.vtk", cube, &damage);
  EXPECT_NE(test::readText(dir / "d.vtk").find("SCALARS damage"), std::string::npos);
  writeTetMesh(dir / "d.node", cube, &damage);
  EXPECT_NE(test::readText(dir / "d.ele").find("6 4 1"), std::string::npos)
      << "damage as the .ele attribute";
}

TEST(MeshFiles, WrongKindsAreClearErrors) {
  EXPECT_THROW_WITH(readTetMesh("x.vtk"), InputError, "output format");
  EXPECT_THROW_WITH(readTetMesh("x.obj"), InputError, "mesh import");
  EXPECT_THROW_WITH(readTetMesh("x.doc"), InputError, "unknown mesh format");
  EXPECT_THROW_WITH(writeTetMesh("x.obj", test::unitCubeTets()), OutputError,
                    "unknown tet mesh format");
}

}  // namespace
}  // namespace galsculpt
