// A simulation in the manner of MuJoCo's mjModel / mjData. SimModel is everything fixed for a
// run (rest mesh, per-element rest data, material, gravity, colliders and their motions, the
// fracture field, edge graph, sparsity pattern and the assembly's fixed-order lists), as flat
// arrays that the executors read as they are: the CPU executor reads them in place, the CUDA one
// copies them to the device once. SimState is everything that changes (positions, velocities,
// damage, plastic state, anchors, rigid pendulums' states, time) and nothing else. StepSettings
// (solver/frame/step.h) holds only numerical settings; the solver owns its scratch memory.
//   SimModel model = buildSimModel(mesh, material);
//   model.gravity = ...; model.colliders = ...; model.fracture = buildFractureField(model, f);
//   SimState state = initialState(model);
//   CpuStepBackend cpu(model);                         // solver/frame/cpu_backend.h
//   StepReport r = cpu.step(state, settings);
// A backend refers to its model: change the model, then make the backend.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "solver/fem/block_sparse.h"
#include "solver/fem/colliders.h"
#include "solver/fem/isotropic_material.h"
#include "solver/fem/plasticity.h"
#include "solver/fem/tet_element.h"
#include "solver/fracture/fracture_field.h"
#include "solver/mesh/tet_mesh.h"
#include "solver/model/anchors.h"

namespace galsculpt {

struct MaterialParams {
  MaterialModel model = MaterialModel::StableNeoHookean;
  Lame lame;
  double density = 1000.0;  // kg/m^3
  PlasticParams plastic;    // yieldStress 0: purely elastic
  // Whether a damaged edge still resists compression (a closed crack bears load): part of the
  // material, fixed for a run (scene: fracture.compression_resists).
  bool compressionResists = true;
  // The crack faces' closing width (Lame::crackWidth; scene: fracture.crack_width).
  double crackWidth = kDefaultCrackWidth;
  // Rayleigh damping D = dampingMass M + dampingStiffness K(x_n).
  double dampingMass = 0.0;       // alpha (1/s)
  double dampingStiffness = 0.0;  // beta (s)

  // The constants the element kernels take: `lame`, with the yield stress and hardening where
  // the model's energy includes its plastic flow (Lame::yield; each element's own yield is this
  // one raised by its hardening, ElementInputs::lame).
  Lame elementLame() const;
};

struct SimModel {
  TetMesh mesh;  // rest configuration
  MaterialParams material;
  std::vector<TetRest> rest;  // (nTets)
  std::vector<double> mass;   // (nVerts) lumped, kg
  std::vector<Edge> edges;    // (nEdges) unique, sorted
  std::vector<std::array<int, 6>>
      tetEdges;                          // (nTets) global edge of each local edge (kTetEdges order)
  BlockPattern pattern;                  // 3x3 blocks: vertex-vertex over mesh edges
  std::vector<TetScatter> scatter;       // (nTets)
  std::vector<std::vector<int>> colors;  // tets grouped so that no two in a group share a vertex
  // The assembly's fixed-order lists (race-free without atomics, the same sums on every
  // executor): each vertex's force and each 3x3 stiffness block is one thread's sum over its
  // own list of element terms: a vertex's in colour order (colour by colour, tets in colour
  // order), a block's in element order (which the host's gather by row ranges keeps,
  // stiffness_gather.h).
  std::vector<int> vertexSlotStart, vertexSlots;  // (nVerts + 1) CSR: 4 t + a of each corner
  std::vector<int> blockSlotStart, blockSlots;    // (nBlocks + 1) CSR: 16 t + 4 a + b
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);           // m/s^2
  std::vector<Collider> colliders;                // with their motions
  FractureField fracture;                         // not enabled: no fracture pass
  // Pieces under this fraction of the body's rest volume are removed from the simulation
  // (solver/fracture/debris.h; scene: fracture.debris); 0 keeps every piece.
  double debrisRemoval = 0.0;

  int numVertices() const { return mesh.numVertices(); }
  int numTets() const { return mesh.numTets(); }
  int numEdges() const { return static_cast<int>(edges.size()); }
  int numBlocks() const { return static_cast<int>(pattern.columns.size()); }
  // The mesh's tets and the tets' edges as flat int arrays (4 and 6 per tet).
  const int* tetVertexArray() const { return mesh.tets.empty() ? nullptr : mesh.tets[0].data(); }
  const int* tetEdgeArray() const { return tetEdges.empty() ? nullptr : tetEdges[0].data(); }
};
static_assert(sizeof(Tet) == 4 * sizeof(int) && sizeof(std::array<int, 6>) == 6 * sizeof(int),
              "tets and tet edges are contiguous ints");
static_assert(sizeof(Vec3) == 3 * sizeof(double), "positions are contiguous doubles");

// Throws std::invalid_argument for a degenerate tet.
SimModel buildSimModel(const TetMesh& mesh, const MaterialParams& material);

// A damaged edge that no blade crossed (SimState::crossing).
inline constexpr float kNoCrossing = -1.0f;
inline bool hasCrossing(float at) {
  return at >= 0.0f && at <= 1.0f;
}

struct SimState {
  std::vector<Vec3> x;                // (nVerts) positions, m
  std::vector<Vec3> v;                // (nVerts) velocities, m/s
  std::vector<std::uint8_t> damaged;  // (nEdges) 1 = damaged for good
  // (nEdges) where a knife crossed a damaged edge, as a fraction along edges[e] from its first
  // vertex to its second (rest configuration); kNoCrossing where no blade crossed it (fracture,
  // or not damaged). The surface puts crack faces through these points (engine/surface_builder).
  std::vector<float> crossing;
  std::uint64_t damageRevision = 0;             // bumped whenever `damaged` or `crossing` changes
  std::vector<Eigen::Matrix3d> plasticInverse;  // (nTets) Fp^-1; empty for elastic materials
  std::vector<double> plasticStrain;            // (nTets) accumulated, for hardening
  std::vector<AnchorConstraint> anchors;        // held vertices and their paths
  // An anchor let go of vertices since the last step (a brush's stroke ended, an anchor was
  // removed or released, vertices unanchored: engine/session/anchor_registry.h says so here).
  // The step's first sub-step then starts from x_n, not from the prediction x_n + h v_n, and
  // the step clears it. Part of the state: snapshots and projects keep it.
  bool letGo = false;
  // (nColliders) the rigid pendulums' angles and angular velocities; missing entries are the
  // colliders' initial states (initialColliderState).
  std::vector<ColliderState> colliders;
  double time = 0.0;  // s
};

SimState initialState(const SimModel& model);

// The damage pattern of one tet as an EdgeDamage bit mask.
EdgeDamage tetDamage(const SimModel& model, const std::vector<std::uint8_t>& damaged, int tet,
                     bool compressionResists);

// Connected parts over undamaged edges (isolated vertices count as their own piece).
int countDamagePieces(const SimModel& model, const SimState& state);

}  // namespace galsculpt
