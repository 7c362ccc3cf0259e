#include "engine/meshing/tetrahedralize.h"

#include <gtest/gtest.h>

#include "solver/io/input_error.h"
#include "solver/io/memory_limits.h"
#include "solver/mesh/mesh_stats.h"
#include "solver/mesh/shape_generators.h"
#include "solver/mesh/surface_checks.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

TEST(Tetrahedralize, SphereLandsWithinTolerance) {
  TetrahedralizeOptions o;
  o.targetTets = 3000;
  const TetrahedralizeResult r = tetrahedralize(makeIcosphere(0.1, 2), o);
  EXPECT_NEAR(r.mesh.numTets(), 3000, 0.15 * 3000);
  const TetMeshStats s = computeStats(r.mesh);
  EXPECT_TRUE(s.watertight);
  EXPECT_EQ(s.pieces, 1);
  EXPECT_NEAR(s.volume, enclosedVolume(makeIcosphere(0.1, 2)), 1e-9)
      << "TetGen fills the surface exactly";
  EXPECT_GT(s.minQuality, 0.05);
}

TEST(Tetrahedralize, CharpyBarAtTwoSizes) {
  for (int target : {2000, 8000}) {
    TetrahedralizeOptions o;
    o.targetTets = target;
    const TetrahedralizeResult r = tetrahedralize(makeCharpyBar(), o);
    EXPECT_NEAR(r.mesh.numTets(), target, 0.15 * target);
  }
}

TEST(Tetrahedralize, ASurfaceFinerThanTheCountAllowsIsSimplified) {
  const TriMesh fine = makeIcosphere(0.1, 5);  // 20480 faces: far more than 3000 tets allow
  TetrahedralizeOptions o;
  o.targetTets = 3000;
  std::vector<std::string> log;
  o.progress = [&](const std::string& line) { log.push_back(line); };
  const TetrahedralizeResult r = tetrahedralize(fine, o);
  EXPECT_NEAR(r.mesh.numTets(), 3000, 0.15 * 3000);
  const TetMeshStats s = computeStats(r.mesh);
  EXPECT_TRUE(s.watertight);
  EXPECT_NEAR(s.volume / enclosedVolume(fine), 1.0, kShapeVolume);
  bool simplified = false;
  for (const std::string& line : log)
    simplified |=
        line.rfind("simplified", 0) == 0 && line.find("faces dropped") != std::string::npos;
  EXPECT_TRUE(simplified);
}

// A latitude-longitude sphere of radius 1 (thin triangles fanning to its poles, as modelling
// programs export them): `rings` x `segments`.
TriMesh uvSphere(int rings, int segments) {
  TriMesh m;
  m.vertices.push_back(Vec3(0, 0, 1));
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      m.vertices.push_back(
          Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  m.vertices.push_back(Vec3(0, 0, -1));
  const int south = m.numVertices() - 1;
  auto at = [&](int i, int j) { return 1 + (i - 1) * segments + j % segments; };
  for (int j = 0; j < segments; ++j) m.faces.push_back({0, at(1, j), at(1, j + 1)});
  for (int i = 1; i < rings - 1; ++i)
    for (int j = 0; j < segments; ++j) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j)
    m.faces.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
  return m;
}

// Simplified to the count's one face per 12 tets (166 faces), the sphere loses 2.8 % of its
// volume: the import keeps more faces, says so, and the tets hold the shape within the bounds.
TEST(Tetrahedralize, ASimplificationThatStraysFromTheShapeKeepsMoreFaces) {
  const TriMesh fine = uvSphere(100, 100);
  ASSERT_TRUE(analyzeSurface(fine).closedManifold());
  TetrahedralizeOptions o;
  o.targetTets = 2000;
  std::vector<std::string> log;
  o.progress = [&](const std::string& line) { log.push_back(line); };
  const TetrahedralizeResult r = tetrahedralize(fine, o);
  const TetMeshStats s = computeStats(r.mesh);
  EXPECT_NEAR(s.volume / enclosedVolume(fine), 1.0, kShapeVolume);
  EXPECT_NEAR(r.mesh.numTets(), 2000, 0.15 * 2000);
  bool strayed = false, kept = false;
  for (const std::string& line : log) {
    strayed |= line.find("keeping more faces") != std::string::npos;
    kept |= line.find("faces dropped") != std::string::npos;
  }
  EXPECT_TRUE(strayed && kept) << ::testing::PrintToString(log);
}

TEST(Tetrahedralize, InsideOutSurfaceIsFlippedNotRejected) {
  TriMesh m = makeIcosphere(1.0, 1);
  for (Tri& f : m.faces) std::swap(f[1], f[2]);
  TetrahedralizeOptions o;
  o.targetTets = 500;
  EXPECT_NEAR(tetrahedralize(m, o).mesh.numTets(), 500, 75);
}

TEST(Tetrahedralize, BadSurfacesSayWhatIsWrong) {
  TetrahedralizeOptions o;
  o.targetTets = 100;
  o.surfaceName = "bad.obj";
  TriMesh open = makeIcosphere(1.0, 1);
  open.faces.pop_back();
  EXPECT_THROW_WITH(tetrahedralize(open, o), InputError,
                    "bad.obj: cannot tetrahedralize: the surface is open");

  TriMesh two = makeIcosphere(1.0, 2);
  const TriMesh copy = two;
  for (const Vec3& v : copy.vertices) two.vertices.push_back(v + Vec3(0.5, 0.1, 0.0));
  for (Tri f : copy.faces)
    two.faces.push_back(
        {f[0] + copy.numVertices(), f[1] + copy.numVertices(), f[2] + copy.numVertices()});
  TetrahedralizeOptions refuse = o;
  refuse.solidifyCrossings = false;
  EXPECT_THROW_WITH(tetrahedralize(two, refuse), InputError, "self-intersecting");

  TriMesh fin = makeIcosphere(1.0, 1);
  fin.vertices.push_back(Vec3(2, 2, 2));
  fin.faces.push_back({fin.faces[0][0], fin.faces[0][1], fin.numVertices() - 1});
  EXPECT_THROW_WITH(tetrahedralize(fin, o), InputError, "non-manifold");
}

TEST(Tetrahedralize, ShellsThroughEachOtherAreMeshedInGroupsThatDoNotCross) {
  // Three balls, the middle one through both others (pieces of an export that overlap): each
  // stays a body of its own, the overlaps as given, the tets shared out by volume.
  const TriMesh ball = makeIcosphere(1.0, 3);
  TriMesh three;
  for (int k = 0; k < 3; ++k) {
    const int base = three.numVertices();
    for (const Vec3& v : ball.vertices) three.vertices.push_back(v + Vec3(1.5 * k, 0.1 * k, 0.0));
    for (Tri f : ball.faces) three.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  }
  TetrahedralizeOptions o;
  o.targetTets = 6000;
  o.surfaceName = "three.obj";
  std::vector<std::string> said;
  o.progress = [&](const std::string& line) { said.push_back(line); };
  const TetrahedralizeResult result = tetrahedralize(three, o);
  EXPECT_NEAR(totalVolume(result.mesh), 3.0 * enclosedVolume(ball),
              0.01 * 3.0 * enclosedVolume(ball));
  EXPECT_NEAR(result.mesh.numTets(), 6000, 0.15 * 6000);
  EXPECT_EQ(computeStats(result.mesh).pieces, 3);
  ASSERT_FALSE(said.empty());
  EXPECT_NE(said[0].find("three.obj: 3 shell(s), some through each other"), std::string::npos)
      << said[0];
  EXPECT_NE(said[0].find("meshed in 2 groups of shells that do not cross"), std::string::npos)
      << said[0];
}

// A crumb pressed into a body (an export whose pieces touch under a compliant crack law): its
// share of the tets by volume is below what its surface allows, so it is meshed as coarse as
// its surface lets it, the body takes its share, and the whole lands within the tolerance.
// A crumb whose least count would throw the whole out of it is refused, saying what it needs.
TEST(Tetrahedralize, ACrumbThroughABodyTakesTheFewestTetsItsSurfaceAllows) {
  const TriMesh body = makeIcosphere(1.0, 3), crumb = makeIcosphere(0.06, 2);
  TriMesh both = body;
  for (const Vec3& v : crumb.vertices) both.vertices.push_back(v + Vec3(0.99, 0.0, 0.0));
  for (Tri f : crumb.faces) {
    for (int& v : f) v += body.numVertices();
    both.faces.push_back(f);
  }
  TetrahedralizeOptions o;
  o.targetTets = 3000;
  o.surfaceName = "crumb.obj";
  std::vector<std::string> said;
  o.progress = [&](const std::string& line) { said.push_back(line); };
  const TetrahedralizeResult result = tetrahedralize(both, o);
  EXPECT_NEAR(result.mesh.numTets(), 3000, 0.15 * 3000);
  EXPECT_EQ(computeStats(result.mesh).pieces, 2);
  bool coarsest = false;
  for (const std::string& line : said)
    coarsest |= line.find(
                    "crumb.obj (group 2 of 2): its share of 1 tets is finer than its "
                    "surface allows: meshed with") != std::string::npos;
  EXPECT_TRUE(coarsest);
  o.targetTets = 40;  // the crumb alone needs more than 15 % of that
  try {
    tetrahedralize(both, o);
    ADD_FAILURE() << "a crumb that needs more than the tolerance leaves is refused";
  } catch (const TetCountUnreachable& e) {
    EXPECT_NE(std::string(e.what()).find("--tets"), std::string::npos) << e.what();
  }
}

TEST(Tetrahedralize, AShellThatCrossesItselfIsMeshedAsTheRegionItEncloses) {
  // A ball with one vertex pulled through to the far side: a spike through the body, the faces
  // around it crossing the others. The region it winds around is meshed, and said.
  TriMesh dented = makeIcosphere(1.0, 3);
  dented.vertices[0] *= -1.5;
  ASSERT_FALSE(findSelfIntersections(dented, 1).empty());
  TetrahedralizeOptions o;
  o.targetTets = 3000;
  o.surfaceName = "dented.obj";
  std::vector<std::string> said;
  o.progress = [&](const std::string& line) { said.push_back(line); };
  const TetrahedralizeResult result = tetrahedralize(dented, o);
  EXPECT_NEAR(result.mesh.numTets(), 3000, 0.15 * 3000);
  EXPECT_NEAR(totalVolume(result.mesh), enclosedVolume(makeIcosphere(1.0, 3)), 0.03 * 4.19);
  ASSERT_FALSE(said.empty());
  EXPECT_NE(said[0].find("1 shell(s) crossing themselves remade as the region they enclose"),
            std::string::npos)
      << said[0];
}

TEST(Tetrahedralize, ACountNoMemoryHoldsIsRefusedBeforeTetGenStarts) {
  // Two billion tets: about 1 TB for TetGen, said before any run (TetGen aborted with "signal
  // 6, instance of 'int'" minutes into a 50M-tet request).
  TetrahedralizeOptions o;
  o.targetTets = 2000000000;
  o.program = "/nonexistent/tetgen";  // never reached
  EXPECT_THROW_WITH(tetrahedralize(makeIcosphere(1.0, 1), o), OutOfMemory,
                    "out of memory before starting: meshing surface to 2000000000 tets "
                    "(TetGen) needs about 1.0 TB; about ");
  EXPECT_NO_THROW(checkMemoryForTets(1000, "small"));
}

// A stand-in for the tetgen program: a shell script of `body` in `dir`; options for 100 tets
// that run it.
TetrahedralizeOptions fakeTetgen(const test::TempDir& dir, const std::string& body) {
  const auto fake = dir / "fake-tetgen";
  test::writeText(fake, "#!/bin/sh\n" + body);
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  TetrahedralizeOptions o;
  o.targetTets = 100;
  o.program = fake.string();
  return o;
}

TEST(Tetrahedralize, TetGenRunningOutOfMemoryIsSaidAsSuch) {
  test::TempDir dir;
  const TetrahedralizeOptions o = fakeTetgen(dir, "echo 'Error:  Out of memory.'\nkill -ABRT $$\n");
  EXPECT_THROW_WITH(tetrahedralize(makeIcosphere(1.0, 1), o), std::runtime_error,
                    "tetgen ran out of memory (crashed with signal 6");
}

TEST(Tetrahedralize, CrashAndTimeoutOfTheProgramAreReported) {
  test::TempDir dir;
  TetrahedralizeOptions o = fakeTetgen(dir, "kill -ABRT $$\n");
  EXPECT_THROW_WITH(tetrahedralize(makeIcosphere(1.0, 1), o), std::runtime_error,
                    "crashed with signal 6");

  o = fakeTetgen(dir, "sleep 20\n");
  o.timeoutSeconds = 0.5;
  EXPECT_THROW_WITH(tetrahedralize(makeIcosphere(1.0, 1), o), std::runtime_error, "timed out");

  o.program = (dir / "missing").string();
  EXPECT_THROW_WITH(tetrahedralize(makeIcosphere(1.0, 1), o), std::runtime_error,
                    "is TetGen installed?");
}

}  // namespace
}  // namespace galsculpt
