#include "solver/frame/step.h"

#include "solver/fem/plasticity.h"
#include "solver/frame/frame_loop.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace galsculpt {

// CHOLMOD's supernodal Cholesky (through Eigen) factors the 3D stiffness matrices about ten
// times faster than Eigen's simplicial LDLT: the reference solver needs it on 35k-tet meshes.
struct StepWorkspace {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> ldlt;
  bool analyzed = false;
  std::unique_ptr<Multigrid> multigrid;  // built once per mesh and grid setup
  // Matrices on the model's fixed pattern, allocated once: the elastic stiffness, the stiffness
  // frozen at x_n for Rayleigh damping (only with several Newton iterations), the system.
  std::unique_ptr<BlockSparseMatrix> stiffness, frozen, system;
  std::vector<int> multigridHandles;
};

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

Eigen::VectorXd flatten(const std::vector<Vec3>& v) {
  Eigen::VectorXd out(3 * v.size());
  for (size_t i = 0; i < v.size(); ++i) out.segment<3>(3 * i) = v[i];
  return out;
}

void unflatten(const Eigen::VectorXd& in, std::vector<Vec3>& v) {
  for (size_t i = 0; i < v.size(); ++i) v[i] = in.segment<3>(3 * i);
}

// One backward-Euler sub-step of length h from `state`; false when it failed (NaN, no descent).
SubstepOutcome substep(const SimModel& model, SimState& state, const StepSettings& s, double h,
                       StepWorkspace& ws) {
  SubstepOutcome result;
  const int n = model.numVertices();
  const Eigen::VectorXd xn = flatten(state.x);
  const Eigen::VectorXd vn = flatten(state.v);
  Eigen::VectorXd mass(3 * n), fext(3 * n);
  for (int i = 0; i < n; ++i) {
    mass.segment<3>(3 * i).setConstant(model.mass[i]);
    fext.segment<3>(3 * i) = model.mass[i] * s.gravity;
  }
  const Eigen::VectorXd xhat = xn + h * vn;

  // Anchored DOFs start (and stay) on their prescribed path.
  std::vector<char> fixed(n, 0);
  Eigen::VectorXd x = xn;
  for (const AnchorConstraint& a : s.anchors) {
    const Vec3 offset = anchorOffset(a, state.time + h);
    for (size_t i = 0; i < a.vertices.size(); ++i) {
      const int v = a.vertices[i];
      fixed[v] = 1;
      x.segment<3>(3 * v) = (a.origin.empty() ? model.mesh.vertices[v] : a.origin[i]) + offset;
    }
  }

  if (!ws.stiffness) {
    ws.stiffness = std::make_unique<BlockSparseMatrix>(model.pattern);
    ws.system = std::make_unique<BlockSparseMatrix>(model.pattern);
  }
  BlockSparseMatrix& k = *ws.stiffness;
  BlockSparseMatrix& hm = *ws.system;
  // beta K(x_n) for Rayleigh damping: the stiffness itself when it is assembled only once.
  const BlockSparseMatrix* frozen = &k;
  auto dampedProduct = [&](const Eigen::VectorXd& dx, Eigen::VectorXd& out) {
    frozen->multiply(dx, out);
    out *= s.dampingStiffness;
  };
  Eigen::VectorXd gradient(3 * n);
  const double modelSize = std::max(boundingBox(model.mesh.vertices).size().norm(), 1e-12);
  // The residual's yardstick: the body's weight, or (without gravity) what it would weigh under
  // standard gravity - the same number for a body under 1 g.
  const double weight = std::max(fext.norm(), 9.81 * mass.norm() / std::sqrt(3.0));

  // Penalty contact with the colliders posed at the end of the sub-step (colliders.h).
  const double contactTime = state.time + h;
  auto contact = [&](const Eigen::VectorXd& y, Eigen::VectorXd* grad, BlockSparseMatrix* hess,
                     std::vector<Vec3>* forces) {
    double energy = 0.0;
    for (size_t c = 0; c < s.colliders.size(); ++c) {
      const Collider& col = s.colliders[c];
      for (int v = 0; v < n; ++v) {
        if (fixed[v]) continue;
        const ContactSample cs = colliderDistance(col, y.segment<3>(3 * v), contactTime);
        if (cs.distance >= 0.0) continue;
        const double stiffness = col.contactStiffness * model.mass[v] / (h * h);
        energy += 0.5 * stiffness * cs.distance * cs.distance;
        if (grad) grad->segment<3>(3 * v) += stiffness * cs.distance * cs.normal;
        if (hess)
          hess->blocks[model.pattern.diagonal[v]] += stiffness * cs.normal * cs.normal.transpose();
        if (forces) (*forces)[c] -= stiffness * cs.distance * cs.normal;
      }
    }
    return energy;
  };

  auto objective = [&](const Eigen::VectorXd& y, double elastic, const Eigen::VectorXd& dampedK) {
    const Eigen::VectorXd inertia = y - xhat;
    const Eigen::VectorXd dx = y - xn;
    return 0.5 / (h * h) * inertia.dot(mass.cwiseProduct(inertia)) + elastic - fext.dot(y) +
           0.5 / h * (s.dampingMass * dx.dot(mass.cwiseProduct(dx)) + dx.dot(dampedK));
  };

  double trialEnergy = 0.0;  // elastic energy at the accepted iterate
  Eigen::VectorXd trialGradient = Eigen::VectorXd::Zero(3 * n);  // and its gradient
  double acceptedEnergy = 0.0;  // the same at the last accepted iterate
  Eigen::VectorXd acceptedGradient = Eigen::VectorXd::Zero(3 * n);
  for (int it = 0; it < s.newtonIterations; ++it) {
    std::vector<Vec3> positions(n);
    unflatten(x, positions);
    auto t0 = Clock::now();
    const double elastic =
        assembleElastic(model, positions, state, s.compressionResists, gradient, &k);
    result.msElements += msSince(t0);
    if (it == 0 && s.newtonIterations > 1) {
      if (!ws.frozen) ws.frozen = std::make_unique<BlockSparseMatrix>(model.pattern);
      ws.frozen->blocks = k.blocks;
      frozen = ws.frozen.get();
    }
    const double elasticAndContact = elastic + contact(x, &gradient, nullptr, nullptr);
    Eigen::VectorXd dampedK;  // beta K0 (x - x_n)
    dampedProduct(x - xn, dampedK);
    const Eigen::VectorXd dx = x - xn;
    Eigen::VectorXd g = mass.cwiseProduct(x - xhat) / (h * h) + gradient - fext +
                        (s.dampingMass * mass.cwiseProduct(dx) + dampedK) / h;
    for (int v = 0; v < n; ++v) {
      if (fixed[v]) g.segment<3>(3 * v).setZero();
    }
    if (!g.allFinite() || !std::isfinite(elastic)) {
      result.ok = false;
      return result;
    }

    // H = M/h^2 + K + (alpha M + beta K0)/h, anchored rows and columns replaced by identity.
    t0 = Clock::now();
    const double betaOverH = s.dampingStiffness / h;
#pragma omp parallel for schedule(static)
    for (size_t b = 0; b < k.blocks.size(); ++b)
      hm.blocks[b] = k.blocks[b] + betaOverH * frozen->blocks[b];
    contact(x, nullptr, &hm, nullptr);
    for (int v = 0; v < n; ++v) {
      hm.blocks[model.pattern.diagonal[v]] +=
          model.mass[v] * (1.0 / (h * h) + s.dampingMass / h) * Eigen::Matrix3d::Identity();
    }
    for (int r = 0; r < n; ++r) {
      for (int kk = model.pattern.rowStart[r]; kk < model.pattern.rowStart[r + 1]; ++kk) {
        const int c = model.pattern.columns[kk];
        // Scaled like the inertia term, so that coarse levels see anchors as stiff.
        if (fixed[r] || fixed[c])
          hm.blocks[kk] = Eigen::Matrix3d::Identity() * (r == c ? model.mass[r] / (h * h) : 0.0);
      }
    }
    Eigen::VectorXd delta;
    if (s.multigrid) {
      if (!ws.multigrid || ws.multigridHandles != s.gridHandles) {
        ws.multigrid = std::make_unique<Multigrid>(model.pattern, model.mesh.vertices, model.edges,
                                                   s.gridHandles);
        ws.multigridHandles = s.gridHandles;
      }
      if (s.multigridSettings.splitAggregates)
        ws.multigrid->updateDamage(model.edges, state.damaged, state.damageRevision);
      ws.multigrid->refresh(hm, s.multigridSettings);
      delta = Eigen::VectorXd::Zero(3 * n);
      const MultigridReport mr = ws.multigrid->solve(hm, -g, delta, s.multigridSettings);
      result.linearResidualReduction =
          mr.initialResidual > 0.0 ? mr.finalResidual / mr.initialResidual : 0.0;
      for (int v = 0; v < n; ++v) {
        if (fixed[v]) delta.segment<3>(3 * v).setZero();
      }
    } else {
      const Eigen::SparseMatrix<double> a = hm.toEigen();
      if (!ws.analyzed) {
        ws.ldlt.analyzePattern(a);
        ws.analyzed = true;
      }
      ws.ldlt.factorize(a);
      if (ws.ldlt.info() != Eigen::Success) {
        result.ok = false;
        return result;
      }
      delta = ws.ldlt.solve(-g);
    }
    result.msSolve += msSince(t0);
    if (!delta.allFinite()) {
      result.ok = false;
      return result;
    }
    ++result.iterations;

    // Backtrack along the Newton direction until the incremental potential decreases: with
    // lineSearch, by the Armijo condition; otherwise (the paper's one-step solver) only when the
    // full step would increase it, which is what turns a huge load into an explosion.
    const double e0 = objective(x, elasticAndContact, dampedK);
    const double slope = g.dot(delta);
    const double sufficient = s.lineSearch ? 1e-4 : 0.0;
    double stepLength = 1.0;
    while (true) {
      const Eigen::VectorXd trial = x + stepLength * delta;
      std::vector<Vec3> tp(n);
      unflatten(trial, tp);
      trialEnergy = assembleElastic(model, tp, state, s.compressionResists, trialGradient, nullptr);
      Eigen::VectorXd trialDampedK;
      dampedProduct(trial - xn, trialDampedK);
      const double e1 =
          objective(trial, trialEnergy + contact(trial, nullptr, nullptr, nullptr), trialDampedK);
      if (std::isfinite(e1) && e1 <= e0 + sufficient * stepLength * slope + 1e-12 * std::abs(e0))
        break;
      stepLength *= 0.5;
      ++result.backtracks;
      if (stepLength < 1e-8) break;
    }
    if (stepLength < 1e-8) {
      // No descent along the Newton direction. From the start of the sub-step that is a
      // failure (rolled back and halved); after accepted iterations it means the iterate sits
      // at the potential's minimum as far as rounding or a kink (a damaged edge switching
      // between tension and compression) allows: keep it.
      if (result.iterations == 1) {
        result.ok = false;
        return result;
      }
      break;
    }
    x += stepLength * delta;
    acceptedEnergy = trialEnergy;
    std::swap(acceptedGradient, trialGradient);
    if (delta.lpNorm<Eigen::Infinity>() * stepLength < s.tolerance * modelSize) break;
  }

  result.energy = acceptedEnergy;
  {
    // Residual of the backward-Euler equations at the accepted positions (free DOFs), relative
    // to the body's weight: how far this frame is from the exact implicit solution.
    Eigen::VectorXd dampedK;
    dampedProduct(x - xn, dampedK);
    Eigen::VectorXd g = mass.cwiseProduct(x - xhat) / (h * h) + acceptedGradient - fext +
                        (s.dampingMass * mass.cwiseProduct(x - xn) + dampedK) / h;
    contact(x, &g, nullptr, nullptr);
    for (int v = 0; v < n; ++v) {
      if (fixed[v]) g.segment<3>(3 * v).setZero();
    }
    result.residual = g.norm() / weight;
  }
  result.contactForces.assign(s.colliders.size(), Vec3::Zero());
  contact(x, nullptr, nullptr, &result.contactForces);
  if (!x.allFinite() || !std::isfinite(result.energy)) {
    result.ok = false;
    return result;
  }
  const Eigen::VectorXd v = (x - xn) / h;
  unflatten(x, state.x);
  unflatten(v, state.v);
  state.time += h;
  return result;
}

// Radial return on every undamaged element after a sub-step; returns how many flowed. A
// damaged element's F spans its crack (the far side moves with another piece, or a slit
// opens): flowing by it would build the crack's opening into the element's rest shape, which
// then pulls on the near side (a cut clay ball crumpled as its halves parted). Damaged
// elements keep the plastic state they had when they were damaged.
int plasticUpdate(const SimModel& model, SimState& state) {
  int flowed = 0;
#pragma omp parallel for schedule(static) reduction(+ : flowed)
  for (int t = 0; t < model.numTets(); ++t) {
    bool damaged = false;
    for (int e : model.tetEdges[t]) damaged = damaged || state.damaged[e];
    if (damaged) continue;
    const Tet& tet = model.mesh.tets[t];
    const TetPoints p{state.x[tet[0]], state.x[tet[1]], state.x[tet[2]], state.x[tet[3]]};
    const Eigen::Matrix3d f = deformationGradient(model.rest[t], p);
    flowed += plasticReturn(model.material.lame, model.material.plastic, f, state.plasticInverse[t],
                            state.plasticStrain[t]);
  }
  return flowed;
}

}  // namespace

Vec3 anchorOffset(const AnchorConstraint& anchor, double time) {
  const auto& p = anchor.path;
  if (p.empty()) return Vec3::Zero();
  if (time <= p.front().time) return p.front().offset;
  if (time >= p.back().time) return p.back().offset;
  const auto it = std::upper_bound(p.begin(), p.end(), time,
                                   [](double t, const AnchorKey& k) { return t < k.time; });
  const AnchorKey& b = *it;
  const AnchorKey& a = *(it - 1);
  const double u = (time - a.time) / (b.time - a.time);
  return (1.0 - u) * a.offset + u * b.offset;
}

StepSettings referenceSettings(StepSettings base) {
  base.newtonIterations = 50;
  base.lineSearch = true;
  base.tolerance = 1e-10;
  return base;
}

double assembleElastic(const SimModel& model, const std::vector<Vec3>& x, const SimState& state,
                       bool compressionResists, Eigen::VectorXd& gradient,
                       BlockSparseMatrix* hessian) {
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
      const EdgeDamage d = tetDamage(model, state.damaged, t, compressionResists);
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

namespace {

// The CPU backend's operations for the shared frame loop (frame_loop.h).
struct CpuFrameOps {
  const SimModel& model;
  SimState& state;
  const StepSettings& settings;

  SimState save() const { return state; }
  void restore(const SimState& saved, bool keepDamage) {
    if (!keepDamage) {
      state = saved;
      return;
    }
    std::vector<std::uint8_t> damaged = std::move(state.damaged);
    const std::uint64_t revision = state.damageRevision;
    state = saved;
    state.damaged = std::move(damaged);
    state.damageRevision = revision;
  }
  SubstepOutcome substep(double h) {
    return galsculpt::substep(model, state, settings, h, *state.workspace);
  }
  bool plastic() const { return !state.plasticInverse.empty(); }
  int plasticUpdate() { return galsculpt::plasticUpdate(model, state); }
  FractureReport fracturePass() {
    return galsculpt::fracturePass(model, *settings.fracture, state, settings.compressionResists);
  }
  double time() const { return state.time; }
  void setTime(double t) { state.time = t; }
};

}  // namespace

StepReport step(const SimModel& model, SimState& state, const StepSettings& settings) {
  if (!state.workspace) state.workspace = std::make_shared<StepWorkspace>();
  CpuFrameOps ops{model, state, settings};
  return runFrame(ops, settings);
}

}  // namespace galsculpt
