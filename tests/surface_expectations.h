// Assertions on surfaces shared by the solver and engine tests.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "solver/mesh/surface_checks.h"

namespace galsculpt::test {

// One closed, consistently oriented, self-intersection-free piece enclosing positive volume.
inline void expectClosedEmbedded(const TriMesh& m) {
  const SurfaceTopology topo = analyzeSurface(m);
  EXPECT_TRUE(topo.closedManifold()) << topo.describeProblem();
  EXPECT_EQ(topo.pieces, 1);
  EXPECT_TRUE(findSelfIntersections(m, 1).empty());
  EXPECT_GT(enclosedVolume(m), 0.0) << "outward orientation";
}

// The triangles of an OBJ file by their vertex indices, as tools that keep the file's indexing
// (Blender, MeshLab) see them; readSurface instead welds equal positions, which closes any
// crack whose two sides still touch. Reads `v` and `f a[/..] b[/..] c[/..]` lines only.
inline TriMesh readObjByIndex(const std::string& path) {
  TriMesh m;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::istringstream tokens(line);
    std::string kind;
    tokens >> kind;
    if (kind == "v") {
      Vec3 p;
      tokens >> p.x() >> p.y() >> p.z();
      m.vertices.push_back(p);
    } else if (kind == "f") {
      Tri f;
      for (int& v : f) {
        std::string corner;
        tokens >> corner;
        v = std::stoi(corner.substr(0, corner.find('/'))) - 1;
      }
      m.faces.push_back(f);
    }
  }
  return m;
}

}  // namespace galsculpt::test
