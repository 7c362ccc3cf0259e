// --reference-dir's store (app/cli/bench_command.cpp): the reference runs of bench's scenes kept
// between runs, under a key of everything they depend on.
#include "app/cli/bench_reference.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "solver/frame/step.h"
#include "solver/io/atomic_file.h"
#include "solver/model/solver_options.h"

namespace galsculpt {

namespace fs = std::filesystem;

std::uint64_t referenceKey(const SceneDescription& scene, const TetMesh& mesh, int frames,
                           const std::vector<int>& settles, int cuts) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, size_t bytes) {
    for (size_t i = 0; i < bytes; ++i) {
      h ^= static_cast<const unsigned char*>(data)[i];
      h *= 1099511628211ull;
    }
  };
  const std::string text = scene.source.dump() + "|" + enumName(scene.solver.preset) + "|" +
                           debrisRuleName(scene.fracture.debris);
  mix(text.data(), text.size());
  // What the scene leaves to a default the physics may change: the crack faces' closing law;
  // and what the reference is (its iteration cap and step test).
  mix(&scene.fracture.crackWidth, sizeof scene.fracture.crackWidth);
  const StepSettings reference = referenceSettings(StepSettings{});
  mix(&reference.newtonIterations, sizeof reference.newtonIterations);
  mix(&reference.tolerance, sizeof reference.tolerance);
  mix(mesh.vertices.data(), mesh.vertices.size() * sizeof(Vec3));
  mix(mesh.tets.data(), mesh.tets.size() * sizeof(mesh.tets[0]));
  mix(&frames, sizeof frames);
  mix(settles.data(), settles.size() * sizeof(int));
  if (cuts > 0) mix(&cuts, sizeof cuts);  // (uncut scenes keep the keys they had)
  return h;
}

ReferenceCache::ReferenceCache(const fs::path& dir, const std::string& scene, std::uint64_t key) {
  std::ostringstream name;
  name << scene << '-' << std::hex << key;
  base_ = dir / name.str();
}
bool ReferenceCache::load(const fs::path& refFile, nlohmann::json& rows) const {
  std::error_code ec;
  if (!fs::exists(file(".json"), ec) || !fs::exists(file(".ref"), ec) ||
      !fs::exists(file(".ref.motion"), ec))
    return false;
  std::ifstream in(file(".json"));
  rows = nlohmann::json::parse(in, nullptr, false);
  if (rows.is_discarded() || !rows.is_array()) return false;
  fs::copy_file(file(".ref"), refFile, fs::copy_options::overwrite_existing);
  fs::copy_file(file(".ref.motion"), fs::path(refFile).concat(".motion"),
                fs::copy_options::overwrite_existing);
  return true;
}
void ReferenceCache::store(const fs::path& refFile, const nlohmann::json& rows) const {
  for (const nlohmann::json& r : rows)
    if (r.contains("error")) return;
  for (const char* ext : {".ref", ".ref.motion"}) {
    const fs::path from =
        ext == std::string(".ref") ? refFile : fs::path(refFile).concat(".motion");
    std::ifstream in(from, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    writeFileAtomically(file(ext), [&](std::ostream& o) { o << bytes; });
  }
  writeFileAtomically(file(".json"), [&](std::ostream& o) { o << rows.dump(2) << '\n'; });
}

PositionError positionError(const std::vector<Vec3>& x, const TetMesh& mesh, bool reference,
                            const fs::path& referencePositions) {
  if (reference) {
    writeFileAtomically(referencePositions, [&](std::ostream& out) {
      out.write(reinterpret_cast<const char*>(x.data()),
                static_cast<std::streamsize>(x.size() * sizeof(Vec3)));
    });
    return {0.0, 0.0};
  }
  std::vector<Vec3> ref(x.size());
  std::ifstream in(referencePositions, std::ios::binary);
  in.read(reinterpret_cast<char*>(ref.data()),
          static_cast<std::streamsize>(ref.size() * sizeof(Vec3)));
  if (!in || x.empty()) return {};
  double largest = 0.0, squares = 0.0, disp = 0.0;
  for (size_t v = 0; v < x.size(); ++v) {
    const double d = (x[v] - ref[v]).norm();
    largest = std::max(largest, d);
    squares += d * d;
    disp = std::max(disp, (ref[v] - mesh.vertices[v]).norm());
  }
  const double scale = std::max(disp, 1e-300);
  return {largest / scale, std::sqrt(squares / static_cast<double>(x.size())) / scale};
}

}  // namespace galsculpt
