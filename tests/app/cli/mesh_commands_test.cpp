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
