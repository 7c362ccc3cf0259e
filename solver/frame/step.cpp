#include "solver/frame/step.h"

#include <algorithm>

#include "solver/fem/hencky_strain.h"
#include "solver/fem/tet_element.h"
#include "solver/frame/parallel.h"

namespace galsculpt {

StepSettings::StepSettings() : SolverOptions(solverPreset(SolverPreset::Paper)) {
  type = SolverType::Reference;  // a direct solve
  acceleratedStart = true;       // (read only with predictedStart)
}

StepSettings stepSettings(const SolverOptions& o, double dt, int substeps) {
  StepSettings s;
  static_cast<SolverOptions&>(s) = o;
  s.dt = dt;
  s.substeps = substeps;
  if (o.type == SolverType::Reference) return referenceSettings(s);
  s.gridHandles = parseGridSetup(o.grid);
  return s;
}

StepSettings referenceSettings(StepSettings base) {
  base.type = SolverType::Reference;  // a direct solve
  // A cap that only ends a sub-step that will not converge: where a crushed element's true
  // Hessian is indefinite the projected Newton matrix is stiffer than it, and Newton converges
  // linearly (Charpy's crack running under the smooth law: 0.945 an iteration, 170 iterations).
  base.newtonIterations = 400;
  base.lineSearch = true;
  base.tolerance = 1e-10;
  base.residualTolerance = 0.0;  // Newton runs to its step test, not to the default's residual
  base.frameBudgetMs = 0.0;
  base.reuseStiffness = false;
  base.localNewton = false;              // the reference solves the whole body every iteration
  base.energyGuard = EnergyGuard::Body;  // and backs off the whole step (a plain line search)
  base.stiffnessTolerance = 0.0;         // and evaluates every element's stiffness
  return base;
}

namespace {

// Element t at positions x under the state's damage and plastic rest shape.
void evaluateTetAt(const SimModel& model, const std::vector<Vec3>& x, const SimState& state, int t,
                   HessianMode mode, ElementEval& ev) {
  const Tet& tet = model.mesh.tets[t];
  const TetPoints p{x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]};
  const EdgeDamage d = tetDamage(model, state.damaged, t, model.material.compressionResists);
  // A plastically deformed element measures strain from its new rest shape, and its yield
  // stress has grown with its hardening (ElementInputs::lame, as the frame does).
  const Lame lame =
      state.plasticStrain.empty()
          ? model.material.elementLame()
          : kernels::hardenedLame(model.material.elementLame(), state.plasticStrain[t]);
  const bool plastic = !state.plasticInverse.empty() && !state.plasticInverse[t].isIdentity(0.0);
  if (plastic) {
    const TetRest r = plasticRest(model.rest[t], state.plasticInverse[t]);
    evaluateElement(model.material.model, lame, r, p, d, mode, ev);
  } else {
    evaluateElement(model.material.model, lame, model.rest[t], p, d, mode, ev);
  }
}

}  // namespace

double assembleElastic(const SimModel& model, const std::vector<Vec3>& x, const SimState& state,
                       Eigen::VectorXd& gradient, BlockSparseMatrix* hessian) {
  gradient.setZero(3 * model.numVertices());
  if (hessian) hessian->setZero();
  std::vector<double> energies(model.numTets(), 0.0);
  const HessianMode mode = hessian ? HessianMode::ProjectedSpd : HessianMode::None;
  for (const std::vector<int>& color : model.colors) {
    // A colour's tets share no vertex: each adds into its own vertices' entries.
    parallelFor(
        static_cast<int>(color.size()),
        [&](int i) {
          const int t = color[i];
          const Tet& tet = model.mesh.tets[t];
          ElementEval ev;
          evaluateTetAt(model, x, state, t, mode, ev);
          energies[t] = ev.energy;
          for (int a = 0; a < 4; ++a)
            gradient.segment<3>(3 * tet[a]) += ev.gradient.segment<3>(3 * a);
          if (hessian) {
            for (int a = 0; a < 4; ++a) {
              for (int b = 0; b < 4; ++b)
                hessian->blocks[model.scatter[t][4 * a + b]] +=
                    ev.hessian.block<3, 3>(3 * a, 3 * b);
            }
          }
        },
        400);
  }
  double total = 0.0;
  for (double e : energies) total += e;
  return total;
}

Vec3 elasticGradientSum(const SimModel& model, const std::vector<Vec3>& x, const SimState& state,
                        const std::vector<int>& vertices) {
  std::vector<int> set = vertices;
  std::sort(set.begin(), set.end());
  set.erase(std::unique(set.begin(), set.end()), set.end());
  // Membership by binary search in the sorted set: a load anchor's few hundred vertices, not a
  // flag per vertex of the body allocated and cleared every frame.
  auto in = [&](int v) { return std::binary_search(set.begin(), set.end(), v); };
  Vec3 sum = Vec3::Zero();
  // Each element touching the set once (at its first corner in the set), all its corners in the
  // set summed, in vertex order: the same sum on every run.
  for (const int v : set) {
    for (int k = model.vertexSlotStart[v]; k < model.vertexSlotStart[v + 1]; ++k) {
      const int t = model.vertexSlots[k] / 4;
      const Tet& tet = model.mesh.tets[t];
      int first = 0;
      while (!in(tet[first]) && first < 3) ++first;
      if (tet[first] != v) continue;
      ElementEval ev;
      evaluateTetAt(model, x, state, t, HessianMode::None, ev);
      for (int a = 0; a < 4; ++a)
        if (in(tet[a])) sum += ev.gradient.segment<3>(3 * a);
    }
  }
  return sum;
}

}  // namespace galsculpt
