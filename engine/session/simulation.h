// A scene turned into a running simulation: the solver model, its state and step settings,
// plus per-frame metrics. The engine's one place where scene descriptions meet the solver.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/session/anchor_registry.h"
#include "engine/session/body_pieces.h"
#include "engine/session/frame_probes.h"
#include "engine/session/surface_cache.h"
#include "engine/surface/export_surface.h"
#include "engine/surface/surface_builder.h"
#include "solver/fracture/knife.h"
#include "solver/frame/cpu_backend.h"
#include "solver/frame/step.h"

namespace galsculpt {

enum class SolverChoice { FromScene, Reference };

// Everything a sculpting action can change, for undo: positions, velocities, damage, plastic
// state, time and the anchors (with their ids). Restoring one gives back that state exactly.

struct SimulationSnapshot {
  std::vector<Vec3> x, v;                       // (nVerts)
  std::vector<std::uint8_t> damaged;            // (nEdges)
  std::vector<float> crossing;                  // (nEdges) where blades crossed, or kNoCrossing
  std::vector<Eigen::Matrix3d> plasticInverse;  // (nTets) or empty
  std::vector<double> plasticStrain;            // (nTets) or empty
  std::vector<ColliderState> colliders;         // (nColliders) rigid pendulums' angles, speeds
  double time = 0.0;
  int frame = 0;
  std::vector<AnchorConstraint> anchors;
  std::vector<AnchorTag> anchorTags;  // (one per anchor)
  int nextAnchorId = 0;
  bool letGo = false;  // SimState::letGo
  int toolDamage = 0;
  // What the solver carries between frames beyond the state (StepBackend::carriedState).
  std::vector<double> solverCarry;
  std::size_t bytes() const;
};

// A frame's figures: the solver's (FrameStatistics, solver/frame/frame_statistics.h; msTotal
// here is the whole frame's, with the pieces and the surface) and the engine's own.
struct FrameMetrics : FrameStatistics {
  int frame = 0;
  double timeS = 0.0;
  double msOther = 0.0;  // msTotal less the elements, the solve, plasticity and fracture
  double volume = 0.0, volumeChangePct = 0.0;
  double kineticEnergy = 0.0;
  double maxDisplacement = 0.0;
  int damagedEdges = 0, pieces = 0;
  // Retries, a frame not converged, elements inside out and a divergence, counted.
  int warnings = 0;
  double contactForceN = 0.0;  // magnitude of the summed collider forces
  double openingM = 0.0;       // scene measure.opening: distance change of its two vertices, m
  double loadN = 0.0;  // measure.load_collider / load_anchor: that collider's or grip's force, N
  // Pieces under fracture.debris_fraction of the body's rest volume (a piece's rest volume is
  // its vertices' corner cells', what its surface encloses at rest: docs/surface.md), the rest
  // volume they hold (% of the body's), and pieces whose surface encloses no positive volume
  // now (inside out as a whole).
  int debrisPieces = 0;
  double debrisVolumePct = 0.0;
  int invertedPieces = 0;
  double debrisMassKg = 0.0;  // the debris' mass (removed from the simulation by default)
  // The load collider (measure.load_collider): how far its centre has moved from where it
  // started (m), and for a rigid pendulum the energy it has lost (J: kinetic and gravitational,
  // what the body absorbed; 0 for a kinematic collider).
  double strikerDisplacementM = 0.0;
  double absorbedEnergyJ = 0.0;
  // Tool events that acted on nothing this frame (a knife that crossed no edge, a brush that
  // reached no vertex: Playback and SculptSession count ToolApplier's idle reports).
  int idleTools = 0;
};

// Whether the frame left a piece of the body above `tolerance` of its own loads (the metrics'
// piece_residual): a body in two or more pieces, under a solver with a tolerance (the
// reference's is 0: it solves to Newton's step test, and has none to leave a piece above).
inline bool pieceAboveTolerance(const FrameMetrics& m, double tolerance) {
  return tolerance > 0.0 && m.pieces > 1 && m.pieceResidual > tolerance;
}

// The metrics CSV's columns in order (docs/cli.md), each a name and the FrameMetrics field it
// prints: one table feeds the header, the rows and whatever reads the metrics by name.
struct MetricsColumn {
  const char* name;
  std::variant<int FrameMetrics::*, double FrameMetrics::*, bool FrameMetrics::*> field;
};
const std::vector<MetricsColumn>& metricsColumns();

// CSV header and row, in the column order documented in docs/cli.md.
std::string metricsCsvHeader();
std::string metricsCsvRow(const FrameMetrics& m);

// Checks the scene's anchors against a mesh as the simulation will use them: each selects at
// least one vertex and names only vertices that exist (InputError with the JSON path otherwise).
void checkSceneAnchors(const SceneDescription& scene, const TetMesh& mesh);

// Solver-side material from a scene material; throws InputError for an unknown model.
MaterialParams materialFromScene(const MaterialDesc& m, const FractureDesc& fracture = {});

// What a simulation takes for each tet: the model, the state, the solver's matrices and levels,
// the surfaces (docs/notes/2026-12-07-memory-before-starting.md). Checked before one is built.
inline constexpr double kSimulationBytesPerTet = 3000.0;

class Simulation {
 public:
  // Throws InputError (naming the scene and JSON path) for anchors that select nothing or
  // name vertices that do not exist.
  Simulation(const SceneDescription& scene, const TetMesh& mesh,
             SolverChoice choice = SolverChoice::FromScene);
  // The backend refers to the model: a simulation stays where it was made.
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // One frame. Throws Interrupted when a stop (stop_request.h) cuts it short: the state is then
  // the last whole frame's, as if the frame had not begun.
  FrameMetrics advance();

  // Tools (engine/session/playback.h drives them from scripts; the app from the mouse).
  // Damages every edge crossing the blade surface (current positions); returns how many.
  int cut(const std::vector<BladeTriangle>& surface);
  // The anchors (the scene's, scripts', brushes' and anchor paint's): added, moved, released
  // and removed through the registry.
  AnchorRegistry& anchors() { return anchors_; }
  const AnchorRegistry& anchors() const { return anchors_; }
  // Vertices whose rest position the anchor description selects (throws InputError naming
  // the file and JSON path when it selects none).
  std::vector<int> selectVertices(const AnchorDesc& shape, const std::string& file,
                                  const std::string& jsonPath) const;
  // Vertices within `radius` of `center` at the current positions.
  std::vector<int> verticesNear(const Vec3& center, double radius) const;
  // The vertex nearest to `point` at the current positions.
  int nearestVertex(const Vec3& point) const;
  // The pieces now: how many, the debris among them and the rest volume it holds (% of the
  // body's), and how many enclose no positive volume (FrameMetrics' columns).
  struct PieceStats {
    int pieces = 1, debrisPieces = 0, invertedPieces = 0;
    double debrisVolumePct = 0.0, debrisMassKg = 0.0;
  };
  PieceStats pieceStats();
  // The number of the piece (part joined by undamaged edges) `vertex` lies in.
  int pieceOf(int vertex) const { return pieces_.of(vertex); }
  // Whether `vertex` lies in debris that the debris rule removed (fracture.debris: hidden from
  // the surface and exports, held out of the solve).
  bool removed(int vertex) const { return pieces_.removed(vertex); }
  // Per vertex, for the views: the fraction of its edges that are damaged, and the largest
  // tensile edge normal stress (Pa) of the tets around it.
  std::vector<double> vertexDamage() const;
  std::vector<double> vertexStress() const;

  // Undo support: the whole mutable state, and its exact restoration (the damage revision
  // moves on, so that the surface and the solver see the change).
  SimulationSnapshot snapshot() const;
  void restore(const SimulationSnapshot& snapshot);
  // Sets the vertices' positions and/or velocities (null: kept), as MuJoCo's qpos / qvel are
  // set; what the solver keeps between frames is dropped where it belonged to the old
  // positions. Throws std::invalid_argument for a size that does not fit or a value that is
  // not finite (nothing changed then).
  void setPositionsAndVelocities(const std::vector<Vec3>* x, const std::vector<Vec3>* v);
  // The checks of setPositionsAndVelocities alone.
  void checkPositionsAndVelocities(const std::vector<Vec3>* x, const std::vector<Vec3>* v) const;

  const SimModel& model() const { return model_; }
  const SimState& state() const { return state_; }
  const StepSettings& settings() const { return settings_; }
  // The backend computing the frames: "cpu" or "cuda" (the notes say why, if not as asked).
  std::string backendName() const { return backend_->name(); }
  // Replaces the backend that computes the frames (tests; an application with its own).
  void setBackend(std::unique_ptr<StepBackend> backend) { backend_ = std::move(backend); }
  // Notes for the user about how the scene is run (e.g. a solver that is not available yet).
  const std::vector<std::string>& notes() const { return notes_; }
  // Why `backend: auto` runs on the CPU (empty when it runs on the GPU or the CPU was asked
  // for): not a note, since the user did not ask for the GPU; bench records it.
  const std::string& backendFallback() const { return backendFallback_; }
  int frame() const { return frame_; }
  // Changes whenever the positions may have changed (a frame, a restore): views and pick
  // structures compare it to know when to refresh.
  std::uint64_t generation() const { return generation_; }
  // The visualization surface (engine/surface/surface_builder.h) at the current damage and
  // positions, brought up to date on each call; `stats` (optional) gets what that update cost.
  const VisualSurface& surface(SurfaceUpdateStats* stats = nullptr) const;
  // The surface as exports write it: one closed shell per piece (removed debris left out),
  // crack sides apart, checked for crossings (engine/surface/export_surface.h).
  ExportedSurface exportSurface() const;
  // What the last update of the surface cost, whoever asked for it: a frame of a body in
  // several pieces brings the surface up to date itself (its inverted-piece count reads it), so
  // a later surface() call finds nothing to do.
  const SurfaceUpdateStats& lastSurfaceUpdate() const { return surface_.lastUpdate(); }
  // Writes the tet mesh at the current positions with its damage: stem.node/.ele/.face,
  // stem.damage (solver/io/damage_io.h) and stem.vtk (cell data: damage, piece). Tets parted
  // between pieces and crushed flat are left out of the .node/.ele set (a reader refuses them;
  // the .vtk keeps every tet); returns how many.
  int writeTetsWithDamage(const std::filesystem::path& stem) const;
  // Volume of the tets that lie inside one piece (all of them until something breaks), and its
  // change from their rest volume.
  double currentVolume() const;
  double volumeChangePercent() const;

 private:
  SimModel model_;
  SimState state_;
  StepSettings settings_;
  std::unique_ptr<StepBackend> backend_;
  std::vector<std::string> notes_;
  std::string backendFallback_;
  std::pair<std::vector<Vec3>, std::vector<Vec3>> lastFinite_;  // x and v before the frame
  // The rest of the state before the frame, brought back with lastFinite_ when a stop leaves
  // the frame unfinished (advance).
  struct FrameStart {
    double time = 0.0;
    std::vector<ColliderState> colliders;
    std::vector<std::uint8_t> damaged;
    std::vector<float> crossing;
    std::vector<Eigen::Matrix3d> plasticInverse;
    std::vector<double> plasticStrain;
    std::uint64_t damageRevision = 0;
    bool whole = false;  // damage and plastic shapes kept too (advance says when)
  };
  FrameStart frameStart_;
  int divergedFrames_ = 0;  // each has a note, up to kDivergenceNotes (its warning counts all)
  static constexpr int kDivergenceNotes = 5;
  // Declared after model_ and state_, which they refer to or are built from.
  AnchorRegistry anchors_;
  BodyPieces pieces_;
  mutable SurfaceCache surface_;
  FrameProbes probes_;
  int toolDamage_ = 0;  // edges cut by tools since the last frame
  void applyInitialVelocity(const InitialVelocityDesc& initial);
  void updatePieces() { pieces_.update(model_, state_); }
  int invertedPieces() const;  // BodyPieces::invertedPieces, the surface built only for two or more
  int frame_ = 0;
  std::uint64_t generation_ = 0;
};

}  // namespace galsculpt
