// The colliders' term of the incremental potential: a penalty on every free vertex inside a
// collider, 1/2 k d^2 with d its (negative) distance to the surface and k = contactStiffness
// m / h^2, so that the penetration a collider allows is the same for every mass and time step.
// Its energy (per vertex, for the vertex guard, and summed), its gradient, its 3x3 diagonal
// stiffness blocks (k n n^T), and the force each collider takes from the body (with a rigid
// pendulum's moment about its axis), summed on the executor and read once per sub-step. The
// poses are placed per sub-step from the colliders' motions; any number of colliders.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/fem/collider_kernels.h"
#include "solver/fem/colliders.h"
#include "solver/fem/dense_kernels.h"
#include "solver/frame/download_span.h"
#include "solver/frame/frame_data.h"
#include "solver/frame/pass_terms.h"
#include "solver/model/sim_model.h"

namespace galsculpt {

template <typename Exec>
class ContactTerm {
 public:
  template <typename T>
  using Buffer = typename Exec::template Buffer<T>;

  ContactTerm(const Exec& ex, const SimModel& model) : ex_(ex), model_(model) {
    sums_.resize(4 * model.colliders.size());
    read_.resize(4 * model.colliders.size());
    perVertex_.resize(model.numVertices());
  }
  explicit ContactTerm(const PassTermContext<Exec>& c) : ContactTerm(c.ex, c.model) {}

  // ---- as a pass term (pass_terms.h) ------------------------------------------------------

  static double* energySlot(FrameScalars* sc, bool trial) {
    return trial ? &sc->trialContact : &sc->contact;
  }
  void atIterate(FrameData<Exec>& d, const double* y, bool, double* gradient) {
    energy(y, d.fixed.data(), d.mass.data(), d.h, gradient, &d.sc()->contact);
  }
  void atTrial(FrameData<Exec>& d, const double* y, const std::uint8_t*, double* gradient) {
    energy(y, d.fixed.data(), d.mass.data(), d.h, gradient, &d.sc()->trialContact);
  }
  void atAccepted(FrameData<Exec>& d, const double* y, double* gradient) {
    atIterate(d, y, false, gradient);
  }
  // Each vertex's energy at the last evaluation's y (x's or the trial's: whichever came last).
  struct VertexShare {
    const double* perVertex;  // null without colliders
    GALSCULPT_HD void add(int v, double& sum) const {
      if (perVertex) sum += perVertex[v];
    }
  };
  VertexShare vertexShare(FrameData<Exec>&, bool) const { return {perVertex()}; }

  // The poses of a sub-step of length h starting at `time`: each rigid pendulum advanced from
  // its state by h at its angular velocity (the step solves against where it will be).
  void place(const std::vector<ColliderState>& states, double time, double h) {
    std::vector<kernels::ColliderPose> poses;
    for (size_t c = 0; c < model_.colliders.size(); ++c) {
      ColliderState at = states[c];
      at.angle += h * at.angularVelocity;
      poses.push_back(colliderPose(model_.colliders[c], time, &at));
    }
    poses_ = poses;
    if (!poses.empty()) poseBuffer_.upload(poses);
  }

  int colliders() const { return static_cast<int>(poses_.size()); }
  // The placed poses in the executor's memory (what captured sections bake in).
  const kernels::ColliderPose* poses() const { return poseBuffer_.data(); }
  // Each vertex's contact energy at the y of the last energy() (null without colliders).
  const double* perVertex() const { return poses_.empty() ? nullptr : perVertex_.data(); }

  // The energy at y into perVertex() and *energy (an executor scalar); its gradient added to
  // `gradient` unless null. Anchored vertices (`fixed`) take none.
  void energy(const double* y, const std::uint8_t* fixed, const double* mass, double h,
              double* gradient, double* energy) {
    const int colliders = this->colliders();
    if (colliders == 0) {
      ex_.forEach(1, [=] GALSCULPT_LAMBDA(int) { *energy = 0.0; });
      return;
    }
    double* perVertex = perVertex_.data();
    const kernels::ColliderPose* poses = poseBuffer_.data();
    ex_.forEach(static_cast<int>(perVertex_.size()), [=] GALSCULPT_LAMBDA(int v) {
      double e = 0.0;
      if (!fixed[v]) {
        for (int c = 0; c < colliders; ++c) {
          double normal[3];
          const double d = kernels::colliderDistance(poses[c], y + 3 * v, normal);
          if (d >= 0.0) continue;
          const double stiffness = poses[c].contactStiffness * mass[v] / (h * h);
          e += 0.5 * stiffness * d * d;
          if (gradient)
            for (int k = 0; k < 3; ++k) gradient[3 * v + k] += stiffness * d * normal[k];
        }
      }
      perVertex[v] = e;
    });
    ex_.sum(
        static_cast<int>(perVertex_.size()), [=] GALSCULPT_LAMBDA(int v) { return perVertex[v]; },
        energy);
  }

  // The stiffness blocks, added inside the system's assembly: Stiffness::add(r, y, block) for
  // a free vertex r's diagonal 3x3 block (column-major).
  struct Stiffness {
    const kernels::ColliderPose* poses;
    int colliders;
    const double* mass;
    double h;
    GALSCULPT_HD void add(int r, const double* y, double out[9]) const {
      for (int ci = 0; ci < colliders; ++ci) {
        double normal[3];
        const double d = kernels::colliderDistance(poses[ci], y + 3 * r, normal);
        if (d >= 0.0) continue;
        const double stiffness = poses[ci].contactStiffness * mass[r] / (h * h);
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) out[i + 3 * j] += stiffness * normal[i] * normal[j];
      }
    }
  };
  Stiffness stiffness(const double* mass, double h) const {
    return {poseBuffer_.data(), colliders(), mass, h};
  }
  using Blocks = Stiffness;
  Blocks diagonalBlocks(FrameData<Exec>& d) const { return stiffness(d.mass.data(), d.h); }

  // Launches the sums of each collider's force on the body at y (and for a rigid pendulum the
  // moment of the body's reaction about its axis); no host read (inside captured sections).
  void sumForces(const double* y, const std::uint8_t* fixed, const double* mass, double h) {
    const kernels::ColliderPose* poses = poseBuffer_.data();
    double* sums = sums_.data();
    const int colliders = this->colliders();
    const int n = static_cast<int>(perVertex_.size());
    for (int ci = 0; ci < colliders; ++ci) {
      for (int k = 0; k < 3; ++k) {
        ex_.sum(
            n,
            [=] GALSCULPT_LAMBDA(int v) {
              double f[3];
              if (fixed[v] || !kernels::contactForce(poses[ci], y + 3 * v, mass[v], h, f))
                return 0.0;
              return f[k];
            },
            sums + 3 * ci + k);
      }
      const ColliderMotion& motion = model_.colliders[ci].motion;
      if (!motion.rigidPendulum()) continue;
      const Vec3 a = motion.axis.normalized();
      const double p0 = motion.pivot.x(), p1 = motion.pivot.y(), p2 = motion.pivot.z();
      const double a0 = a.x(), a1 = a.y(), a2 = a.z();
      ex_.sum(
          n,
          [=] GALSCULPT_LAMBDA(int v) {
            double f[3];
            if (fixed[v] || !kernels::contactForce(poses[ci], y + 3 * v, mass[v], h, f)) return 0.0;
            // The body pushes back with -f at the vertex: ((x - p) x -f) . a
            const double r0 = y[3 * v] - p0, r1 = y[3 * v + 1] - p1, r2 = y[3 * v + 2] - p2;
            const double m0 = r1 * f[2] - r2 * f[1];
            const double m1 = r2 * f[0] - r0 * f[2];
            const double m2 = r0 * f[1] - r1 * f[0];
            return -(m0 * a0 + m1 * a1 + m2 * a2);
          },
          sums + 3 * colliders + ci);
    }
  }

  // Reads what sumForces summed (one host read): each collider's force, N, and each rigid
  // pendulum's moment, N m (0 for other colliders).
  void readForces(std::vector<Vec3>& forces, std::vector<double>& moments) {
    const size_t colliders = poses_.size();
    if (colliders > 0) ex_.read(sums_.data(), read_.data(), static_cast<int>(4 * colliders));
    takeForces(forces, moments);
  }
  // The same read, as a span of a batched download (the sub-step's end's), and what it brought.
  DownloadSpan forcesSpan() {
    return {sums_.data(), read_.data(), 4 * poses_.size() * sizeof(double)};
  }
  void takeForces(std::vector<Vec3>& forces, std::vector<double>& moments) const {
    const size_t colliders = poses_.size();
    forces.assign(colliders, Vec3::Zero());
    moments.assign(colliders, 0.0);
    for (size_t c = 0; c < colliders; ++c) {
      const double* f = &read_[3 * c];
      forces[c] = Vec3(f[0], f[1], f[2]);
      if (model_.colliders[c].motion.rigidPendulum()) moments[c] = read_[3 * colliders + c];
    }
  }

 private:
  const Exec& ex_;
  const SimModel& model_;
  std::vector<kernels::ColliderPose> poses_;
  Buffer<kernels::ColliderPose> poseBuffer_;
  Buffer<double> sums_;       // (4 nColliders) forces, then pendulum moments
  std::vector<double> read_;  // the same, read to the host
  Buffer<double> perVertex_;  // (nVerts) contact energy at the last energy()'s y
};

}  // namespace galsculpt
