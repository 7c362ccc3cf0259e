// A bounded fuzzing run of every reader: a valid seed file per format, mutated at random (fixed
// seeds, so a run is repeatable) by bit flips, byte changes, deletions, duplications,
// truncations and extreme numbers, then read. A reader may accept the result or refuse it with
// InputError; any other exception fails the test, and a crash or hang fails it too (CTest).
// The input being read is always on disk, in the file the reader was given, to reproduce from.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <random>

#include "app/window/input_script.h"
#include "engine/scene/scene.h"
#include "engine/scene/scene_mesh.h"
#include "engine/session/playback.h"
#include "engine/session/project_file.h"
#include "engine/surface/surface_io.h"
#include "solver/io/damage_io.h"
#include "solver/io/gmsh_io.h"
#include "solver/io/input_error.h"
#include "solver/io/tetgen_io.h"
#include "solver/mesh/shape_generators.h"
#include "tests/test_util.h"

namespace galsculpt {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const fs::path kAssets = fs::path(GALSCULPT_SOURCE_DIR) / "assets";

// Iterations per reader, and a time cap so that a slow machine still finishes in bounds.
constexpr int kIterations = 5000;
constexpr double kSecondsPerReader = 20.0;

std::string mutate(const std::string& seed, std::mt19937& rng) {
  static const char* kTokens[] = {
      "-1", "0", "4294967296", "2147483648", "1e999", "nan", "-0",     "99999999999999999999",
      "\n", "[", "{",          "\"",         " ",     "#",   "1e-400", "-2147483649",
      "inf"};
  std::string s = seed;
  std::uniform_int_distribution<int> ops(1, 4), kind(0, 6), byte(0, 255);
  const int n = ops(rng);
  for (int i = 0; i < n && !s.empty(); ++i) {
    std::uniform_int_distribution<size_t> at(0, s.size() - 1);
    switch (kind(rng)) {
      case 0:
        s[at(rng)] ^= static_cast<char>(1 << (byte(rng) % 8));
        break;
      case 1:
        s[at(rng)] = static_cast<char>(byte(rng));
        break;
      case 2:
        s.insert(at(rng), kTokens[byte(rng) % (sizeof(kTokens) / sizeof(kTokens[0]))]);
        break;
      case 3: {
        const size_t p = at(rng);
        s.erase(p, 1 + byte(rng) % 16);
        break;
      }
      case 4: {
        const size_t p = at(rng);
        const std::string chunk = s.substr(p, 1 + byte(rng) % 64);
        s.insert(at(rng), chunk);
        break;
      }
      case 5:
        s.resize(at(rng));
        break;
      case 6: {  // a number replaced by an extreme one
        size_t p = at(rng);
        while (p < s.size() && !std::isdigit(static_cast<unsigned char>(s[p]))) ++p;
        size_t e = p;
        while (e < s.size() && (std::isdigit(static_cast<unsigned char>(s[e])) || s[e] == '.')) ++e;
        if (p < s.size()) s.replace(p, e - p, kTokens[byte(rng) % 8]);
        break;
      }
    }
  }
  return s;
}

// Writes each mutation of `seed` to `file` and calls `read`.
void fuzz(const std::string& name, const fs::path& file, const std::string& seed,
          const std::function<void()>& read) {
  std::mt19937 rng(static_cast<unsigned>(std::hash<std::string>{}(name)));
  const auto start = Clock::now();
  int accepted = 0, refused = 0, done = 0;
  for (; done < kIterations; ++done) {
    if (std::chrono::duration<double>(Clock::now() - start).count() > kSecondsPerReader) break;
    test::writeText(file, mutate(seed, rng));
    try {
      read();
      ++accepted;
    } catch (const InputError&) {
      ++refused;
    } catch (const std::exception& e) {
      const fs::path keep =
          fs::temp_directory_path() /
          ("galsculpt-fuzz-" + name + "-" + std::to_string(done) + file.extension().string());
      fs::copy_file(file, keep, fs::copy_options::overwrite_existing);
      ADD_FAILURE() << name << " iteration " << done << ": " << e.what() << " (input kept in "
                    << keep << ")";
      return;
    }
  }
  std::cout << name << ": " << done << " inputs, " << accepted << " accepted, " << refused
            << " refused\n";
  EXPECT_GT(done, 50) << "too few inputs in the time allowed";
  EXPECT_GT(refused, 0) << "mutations that no reader refuses test nothing";
}

const char* kNode = "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1\n";
const char* kEle = "2 4 0\n0 0 1 2 3\n1 1 2 3 4\n";

TEST(FuzzReaders, TetGen) {
  test::TempDir dir;
  test::writeText(dir / "m.ele", kEle);
  fuzz("tetgen-node", dir / "m.node", kNode, [&] { readTetGen(dir / "m"); });
  test::writeText(dir / "m.node", kNode);
  fuzz("tetgen-ele", dir / "m.ele", kEle, [&] { readTetGen(dir / "m"); });
}

TEST(FuzzReaders, Gmsh) {
  test::TempDir dir;
  writeGmsh(dir / "seed.msh", test::gridBar(2, 2, 2, 0.1));
  fuzz("gmsh", dir / "m.msh", test::readText(dir / "seed.msh"), [&] { readGmsh(dir / "m.msh"); });
}

TEST(FuzzReaders, OffAndPly) {
  test::TempDir dir;
  const TriMesh ball = makeIcosphere(1.0, 1);
  std::string off =
      "OFF\n" + std::to_string(ball.numVertices()) + " " + std::to_string(ball.numFaces()) + " 0\n";
  for (const Vec3& p : ball.vertices)
    off += std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  for (const Tri& f : ball.faces)
    off += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
           "\n";
  fuzz("off", dir / "m.off", off, [&] { readSurface(dir / "m.off"); });
  std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(ball.numVertices()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(ball.numFaces()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
  ply += off.substr(off.find('\n', 4) + 1);
  fuzz("ply-ascii", dir / "m.ply", ply, [&] { readSurface(dir / "m.ply"); });
  writeSurface(dir / "seed.ply", ball);  // binary
  fuzz("ply-binary", dir / "b.ply", test::readText(dir / "seed.ply"),
       [&] { readSurface(dir / "b.ply"); });
}

TEST(FuzzReaders, AssimpFormats) {
  test::TempDir dir;
  const TriMesh ball = makeIcosphere(1.0, 1);
  // Names built by appending: GCC 12 warns falsely (-Wrestrict) on "literal" + string here.
  for (const char* ext : {".obj", ".stl", ".glb"}) {
    const fs::path seed = fs::path(dir / "seed").concat(ext);
    writeSurface(seed, ball);
    const fs::path file = fs::path(dir / "m").concat(ext);
    std::string name = "surface";
    name.append(ext);
    fuzz(name, file, test::readText(seed), [&] { readSurface(file); });
  }
  writeSurface(dir / "g.gltf", ball);  // g.gltf + g.bin: the JSON mutated, the buffer kept
  fuzz("surface.gltf", dir / "g.gltf", test::readText(dir / "g.gltf"),
       [&] { readSurface(dir / "g.gltf"); });
}

TEST(FuzzReaders, SceneAndScript) {
  test::TempDir dir;
  std::string scene = test::readText(kAssets / "scenes" / "default.json");
  const std::string mesh = (kAssets / "meshes" / "sphere_small.node").string();
  scene.replace(scene.find("../meshes/sphere_small.node"), 27, mesh);
  fuzz("scene", dir / "s.json", scene, [&] { loadScene(dir / "s.json"); });
  std::string script = test::readText(kAssets / "scripts" / "sculpted_face.json");
  const std::string sceneFile = (kAssets / "scenes" / "default.json").string();
  const size_t at = script.find("../scenes/");
  ASSERT_NE(at, std::string::npos);
  script.replace(at, script.find('"', at) - at, sceneFile);
  fuzz("script", dir / "p.json", script, [&] { loadPlaybackScript(dir / "p.json"); });
}

TEST(FuzzReaders, InputScript) {
  test::TempDir dir;
  fuzz("input-script", dir / "i.json",
       test::readText(fs::path(GALSCULPT_SOURCE_DIR) / "docs" / "images" /
                      "guide_overview_input.json"),
       [&] { loadInputScript(dir / "i.json"); });
}

TEST(FuzzReaders, ProjectAndDamage) {
  test::TempDir dir;
  const SceneDescription scene = loadScene(kAssets / "scenes" / "default.json");
  SculptSession session(scene, loadSceneMesh(scene));
  session.knife(Vec3(0.02, 0.2, -0.2), Vec3(0.02, 0.2, 0.2), Vec3(0.02, -0.2, -0.2),
                Vec3(0.02, -0.2, 0.2), {});
  session.step();
  writeProject(dir / "seed.gsproj", session, std::nullopt);
  fuzz("project", dir / "p.gsproj", test::readText(dir / "seed.gsproj"),
       [&] { readProject(dir / "p.gsproj"); });
  const Simulation& sim = session.simulation();
  writeDamage(dir / "seed.damage", sim.model().edges, sim.state().damaged, sim.state().crossing);
  fuzz("damage", dir / "d.damage", test::readText(dir / "seed.damage"),
       [&] { readDamage(dir / "d.damage", sim.model().edges); });
}

}  // namespace
}  // namespace galsculpt
