#include "solver/frame/step.h"

#include <algorithm>

#include "solver/fem/tet_element.h"

namespace galsculpt {

StepSettings referenceSettings(StepSettings base) {
  base.newtonIterations = 50;
  base.lineSearch = true;
  base.tolerance = 1e-10;
  base.residualTolerance = 0.0;  // Newton runs to its step test, not to the default's residual
  base.frameBudgetMs = 0.0;
  base.reuseStiffness = false;
  base.vertexGuard = false;       // the reference backs off the whole step (a plain line search)
  base.stiffnessTolerance = 0.0;  // and evaluates every element's stiffness
  return base;
}

double assembleElastic(const SimModel& model, const std::vector<Vec3>& x, const SimState& state,
                       Eigen::VectorXd& gradient, BlockSparseMatrix* hessian) {
  gradient.setZero(3 * model.numVertices());
  if (hessian) hessian->setZero();
  std::vector<double> energies(model.numTets(), 0.0);
  const HessianMode mode = hessian ? HessianMode::ProjectedSpd : HessianMode::None;
  for (const std::vector<int>& color : model.colors) {
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < color.size(); ++i) {
      const int t = color[i];
      const Tet& tet = model.mesh.tets[t];
      const TetPoints p{x[tet[0]], x[tet[1]], x[tet[2]], x[tet[3]]};
      const EdgeDamage d = tetDamage(model, state.damaged, t, model.material.compressionResists);
      ElementEval ev;
      // A plastically deformed element measures strain from its new rest shape.
      const bool plastic =
          !state.plasticInverse.empty() && !state.plasticInverse[t].isIdentity(0.0);
      if (plastic) {
        const TetRest r = plasticRest(model.rest[t], state.plasticInverse[t]);
        evaluateElement(model.material.model, model.material.lame, r, p, d, mode, ev);
      } else {
        evaluateElement(model.material.model, model.material.lame, model.rest[t], p, d, mode, ev);
      }
      energies[t] = ev.energy;
      for (int a = 0; a < 4; ++a) gradient.segment<3>(3 * tet[a]) += ev.gradient.segment<3>(3 * a);
      if (hessian) {
        for (int a = 0; a < 4; ++a) {
          for (int b = 0; b < 4; ++b)
            hessian->blocks[model.scatter[t][4 * a + b]] += ev.hessian.block<3, 3>(3 * a, 3 * b);
        }
      }
    }
  }
  double total = 0.0;
  for (double e : energies) total += e;
  return total;
}

}  // namespace galsculpt
