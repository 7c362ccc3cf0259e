// Project files (.gsproj): a sculpting session saved whole, to be reopened where it was left.
//
// One file, written atomically: a text line naming the format and its version, a JSON header
// (the scene as it was read, the frame and time, the anchors, the camera and the recording of
// every action so far), then the arrays in binary, little-endian: rest vertices, tets,
// positions, velocities, damage per edge, where knife blades crossed each edge (float per edge,
// -1 for none; since version 2), the plastic state when the material has one, and what the
// solver carries between frames beyond the state (the coarsest matrix whose factorization the
// multigrid keeps, `solver_carry` doubles in the header; since version 3), so that a reopened
// project runs on to the same bits as the session that saved it.
// The tet mesh is stored, not referred to, so a project opens without its scene's mesh source.
//
// Versions: this build writes version 3 and reads versions 1 to 3 (a version 1 file has no
// crossings: its cuts show today's crack faces, at edge midpoints; a file before version 3 has
// no solver carry: its first frame factors afresh, to within the tolerance of the frame the
// saving session would have run); a newer file is refused
// with a message saying so. Every malformed file gets an InputError naming the file and what
// is wrong (a header key with its JSON path, or the byte offset of a bad array).
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/session/playback.h"
#include "engine/session/sculpt_session.h"
#include "engine/session/simulation.h"

namespace galsculpt {

constexpr int kProjectVersion = 3;

struct Project {
  SceneDescription scene;
  TetMesh mesh;  // rest configuration
  SimulationSnapshot state;
  std::vector<ToolEvent> recording;
  std::optional<CameraPose> camera;
};

void writeProject(const std::filesystem::path& file, const SceneDescription& scene,
                  const Simulation& sim, const std::vector<ToolEvent>& recording,
                  const std::optional<CameraPose>& camera);
Project readProject(const std::filesystem::path& file);

// Saves a session (its scene, state and recording) with the current view.
void writeProject(const std::filesystem::path& file, const SculptSession& session,
                  const std::optional<CameraPose>& camera);
// A session in the saved state; throws InputError (naming `file`) when the saved state does not
// fit its own mesh.
std::unique_ptr<SculptSession> sessionFromProject(const Project& project,
                                                  const std::filesystem::path& file);

// Whether a file starts like a project (for `galsculpt open`).
bool looksLikeProject(const std::filesystem::path& file);

}  // namespace galsculpt
