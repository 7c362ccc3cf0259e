#include "app/cli/cli.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "engine/surface/surface_io.h"
#include "solver/mesh/shape_generators.h"
#include "tests/app/cli/cli_run.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::run;

TEST(Cli, InfoOfTetMeshAndSurface) {
  test::TempDir dir;
  writeSurface(dir / "s.ply", makeIcosphere(1.0, 2));
  const CliRun surface = run({"mesh", "info", (dir / "s.ply").string()});
  ASSERT_EQ(surface.code, kExitOk) << surface.err;
  EXPECT_NE(surface.out.find("kind: surface"), std::string::npos);
  EXPECT_NE(surface.out.find("faces: 320"), std::string::npos);
  EXPECT_NE(surface.out.find("watertight: yes"), std::string::npos);
  EXPECT_NE(surface.out.find("pieces: 1"), std::string::npos);

  const fs::path tricky = fs::path(GALSCULPT_TEST_DATA) / "valid" / "tricky.node";
  const CliRun tet = run({"mesh", "info", tricky.string(), "--json"});
  ASSERT_EQ(tet.code, kExitOk) << tet.err;
  const auto j = nlohmann::json::parse(tet.out);
  EXPECT_EQ(j["tets"], 2);
  EXPECT_EQ(j["reoriented_tets"], 1);
  EXPECT_EQ(j["pieces"], 1);
  EXPECT_EQ(j["quality_histogram"].size(), 10u);
}

TEST(Cli, InfoFindsACrossingInsideAShellBeyondManyContactPairs) {
  // Five dense spheres through each other (contact: more pairs than the census lists) and a
  // small one with a vertex pushed through its far side: the last is not watertight, however
  // many contact pairs come first.
  TriMesh mesh = makeIcosphere(1.0, 4);
  auto append = [&](TriMesh part, const Vec3& shift) {
    const int base = mesh.numVertices();
    for (const Vec3& p : part.vertices) mesh.vertices.push_back(p + shift);
    for (Tri f : part.faces) {
      for (int& v : f) v += base;
      mesh.faces.push_back(f);
    }
  };
  for (int k = 1; k < 5; ++k) append(makeIcosphere(1.0, 4), Vec3(0.3 * k, 0.011 * k, 0.017 * k));
  TriMesh dented = makeIcosphere(0.2, 1);
  dented.vertices[0] *= -2.0;
  append(dented, Vec3(5.0, 0.0, 0.0));
  test::TempDir dir;
  writeSurface(dir / "s.obj", mesh);
  const CliRun info = run({"mesh", "info", (dir / "s.obj").string()});
  ASSERT_EQ(info.code, kExitOk) << info.err;
  EXPECT_NE(info.out.find("watertight: no (self-intersecting"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("contact: 1000+ crossing face pair(s) between shells"), std::string::npos)
      << info.out;
  EXPECT_EQ(info.out.find("self_intersections: 0"), std::string::npos) << info.out;
}

TEST(Cli, ConvertBetweenFormats) {
  test::TempDir dir;
  const CliRun gen = run({"mesh", "generate", "sphere", (dir / "s.node").string(), "--tets", "2000",
                          "--radius", "0.5"});
  ASSERT_EQ(gen.code, kExitOk) << gen.err;
  for (const char* out : {"s.msh", "s.vtk", "s.obj", "s.stl", "s.glb"}) {
    const CliRun r = run({"mesh", "convert", (dir / "s.node").string(), (dir / out).string()});
    EXPECT_EQ(r.code, kExitOk) << out << ": " << r.err;
    EXPECT_TRUE(fs::exists(dir / out)) << out;
  }
  const CliRun back = run({"mesh", "convert", (dir / "s.msh").string(), (dir / "t.node").string()});
  ASSERT_EQ(back.code, kExitOk) << back.err;
  // The same tets; each set carries its own stamp (its last line).
  auto withoutStamp = [](std::string text) {
    return text.substr(0, text.rfind("# galsculpt set"));
  };
  EXPECT_EQ(withoutStamp(test::readText(dir / "t.ele")),
            withoutStamp(test::readText(dir / "s.ele")));
  const CliRun surf = run({"mesh", "convert", (dir / "s.obj").string(), (dir / "s2.ply").string()});
  EXPECT_EQ(surf.code, kExitOk) << surf.err;
  const CliRun vol = run({"mesh", "convert", (dir / "s.obj").string(), (dir / "s3.node").string()});
  EXPECT_EQ(vol.code, kExitUsage) << "surface to tets needs --tets";
}

TEST(Cli, ImportRejectsAnOpenSurfaceWithExitThree) {
  test::TempDir dir;
  TriMesh open = makeIcosphere(1.0, 2);
  open.faces.resize(open.faces.size() - 4);
  writeSurface(dir / "open.obj", open);
  const CliRun r = run(
      {"mesh", "import", (dir / "open.obj").string(), (dir / "o.node").string(), "--tets", "500"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("the surface is open"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.node"));
}

}  // namespace
}  // namespace galsculpt
