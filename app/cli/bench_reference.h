// --reference-dir (app/cli/bench_command.cpp): a scene's reference rows and positions kept between
// runs. The reference takes seconds a frame, the multigrid milliseconds; on a GPU machine,
// minutes of its time.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

// What a scene's reference run depends on: the scene as read and as modified by the options
// (its solver keys, debris rule), the defaults it leaves that the physics changed (the crack
// width), the reference's own settings (referenceSettings), the mesh, and the frames measured.
// FNV-1a, as the mesh cache.
std::uint64_t referenceKey(const SceneDescription& scene, const TetMesh& mesh, int frames,
                           const std::vector<int>& settles, int cuts);

// The rows (JSON) are written last, so a set missing a part is computed again.
class ReferenceCache {
 public:
  ReferenceCache(const std::filesystem::path& dir, const std::string& scene, std::uint64_t key);
  // The rows and the reference's positions (copied to refFile and refFile.motion), or false.
  bool load(const std::filesystem::path& refFile, nlohmann::json& rows) const;
  // Keeps rows with no error, with refFile's positions.
  void store(const std::filesystem::path& refFile, const nlohmann::json& rows) const;

 private:
  std::filesystem::path file(const char* ext) const {
    return std::filesystem::path(base_).concat(ext);
  }
  std::filesystem::path base_;
};

// How far a run's positions are from the reference's, both relative to the reference's largest
// displacement (-1: no reference). The largest is the contract's figure; the root mean square
// says whether it is the body or a few loose vertices (a flap hanging by one intact edge beside
// a crack is nearly free, and its position is decided by residuals far below the tolerance).
struct PositionError {
  double largest = -1.0;
  double rms = -1.0;
};

// The reference run writes its positions (and scores 0); the others are compared with them.
PositionError positionError(const std::vector<Vec3>& x, const TetMesh& mesh, bool reference,
                            const std::filesystem::path& referencePositions);

}  // namespace galsculpt
