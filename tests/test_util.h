// Shared helpers for the tests: temporary folders, small meshes, error-message assertions.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "solver/frame/cpu_backend.h"
#include "solver/mesh/tet_mesh.h"
#include "solver/model/solver_options.h"

namespace galsculpt::test {

// A fresh folder under the system temp dir, removed with the object.
class TempDir {
 public:
  TempDir() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "galsculpt-test-XXXXXX").string();
    path_ = mkdtemp(pattern.data());
  }
  // GALSCULPT_KEEP_TEST_DIRS keeps them, to look at what a failing test wrote.
  ~TempDir() {
    if (std::getenv("GALSCULPT_KEEP_TEST_DIRS")) return;
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Sets an environment variable for a scope and puts the old value (or its absence) back.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

inline void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// The address space this process has mapped (VmSize), bytes; 0 where it cannot be read.
inline std::uint64_t mappedBytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  std::uint64_t kb = 0;
  while (status >> key)
    if (key == "VmSize:" && status >> kb) return kb * 1024;
  return 0;
}

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The unit cube split into 6 positively oriented tets (Kuhn subdivision), scaled and shifted.
inline TetMesh unitCubeTets(double size = 1.0, const Vec3& origin = Vec3::Zero()) {
  TetMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.push_back(origin + size * Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  }
  // Paths from corner 0 to corner 7 along the axes, one tet per permutation.
  const int perms[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (const auto& p : perms) {
    Tet t{0, p[0], p[0] | p[1], 7};
    if (tetSixVolume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]) < 0) {
      std::swap(t[2], t[3]);
    }
    m.tets.push_back(t);
  }
  return m;
}

// A box of nx x ny x nz cubes of edge `size`, each split into 6 tets (Kuhn), origin at 0.
inline TetMesh gridBar(int nx, int ny, int nz, double size) {
  TetMesh m;
  auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) m.vertices.push_back(size * Vec3(i, j, k));
    }
  }
  const TetMesh cube = unitCubeTets();
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (const Tet& t : cube.tets) {
          Tet g;
          for (int c = 0; c < 4; ++c)
            g[c] = id(i + (t[c] & 1), j + ((t[c] >> 1) & 1), k + ((t[c] >> 2) & 1));
          m.tets.push_back(g);
        }
      }
    }
  }
  return m;
}

}  // namespace galsculpt::test

// Expects `statement` to throw `type` whose what() contains `substring`.
#define EXPECT_THROW_WITH(statement, type, substring)                             \
  do {                                                                            \
    try {                                                                         \
      statement;                                                                  \
      ADD_FAILURE() << "expected " #type " containing '" << (substring) << "'";   \
    } catch (const type& e) {                                                     \
      EXPECT_NE(std::string(e.what()).find(substring), std::string::npos)         \
          << "message: " << e.what() << "\nexpected to contain: " << (substring); \
    }                                                                             \
  } while (0)

namespace galsculpt {

// The converged preset's settings (solver/model/solver_options.h) on a small mesh: 12 coarse
// handles.
inline StepSettings convergedPreset() {
  StepSettings s = stepSettings(solverPreset(SolverPreset::Converged), 1.0 / 60.0, 1);
  s.gridHandles = {12};
  return s;
}

// One frame on a fresh CPU backend: for tests on small meshes (a session keeps its backend and
// the hierarchy in it; the results are the same either way).
inline StepReport step(const SimModel& model, SimState& state, const StepSettings& settings) {
  CpuStepBackend cpu(model);
  return cpu.step(state, settings);
}

// Every edge across the plane x = cut damaged: a grid bar cut through between its layers.
inline void cutAt(const SimModel& m, SimState& s, double cut) {
  for (int e = 0; e < m.numEdges(); ++e) {
    const double a = m.mesh.vertices[m.edges[e][0]].x(), b = m.mesh.vertices[m.edges[e][1]].x();
    if (std::min(a, b) < cut + 1e-9 && std::max(a, b) > cut + 1e-9) s.damaged[e] = 1;
  }
  ++s.damageRevision;
}

}  // namespace galsculpt
