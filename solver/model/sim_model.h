// The fixed part of a simulation (rest mesh, per-element rest data, material, edge graph,
// sparsity pattern, scatter map, element colouring) apart from the changing state (positions,
// velocities, damage). One pipeline of plain functions works on them:
//   SimModel model = buildSimModel(mesh, material);
//   SimState state = initialState(model);
//   CpuStepBackend cpu(model);                         // solver/frame/cpu_backend.h
//   StepReport r = cpu.step(state, settings);
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "solver/fem/block_sparse.h"
#include "solver/fem/isotropic_material.h"
#include "solver/fem/plasticity.h"
#include "solver/fem/tet_element.h"
#include "solver/mesh/tet_mesh.h"

namespace galsculpt {

struct MaterialParams {
  MaterialModel model = MaterialModel::StableNeoHookean;
  Lame lame;
  double density = 1000.0;  // kg/m^3
  PlasticParams plastic;    // yieldStress 0: purely elastic
  // Whether a damaged edge still resists compression (a closed crack bears load): part of the
  // material, fixed for a run (scene: fracture.compression_resists).
  bool compressionResists = true;
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

  int numVertices() const { return mesh.numVertices(); }
  int numTets() const { return mesh.numTets(); }
  int numEdges() const { return static_cast<int>(edges.size()); }
};

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
  double time = 0.0;                            // s
};

SimState initialState(const SimModel& model);

// The damage pattern of one tet as an EdgeDamage bit mask.
EdgeDamage tetDamage(const SimModel& model, const std::vector<std::uint8_t>& damaged, int tet,
                     bool compressionResists);

// Connected parts over undamaged edges (isolated vertices count as their own piece).
int countDamagePieces(const SimModel& model, const SimState& state);

}  // namespace galsculpt
