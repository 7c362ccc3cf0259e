#include "engine/session/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "engine/scene/scene_mesh.h"
#include "engine/session/backend_select.h"
#include "solver/frame/timing.h"
#include "solver/io/input_error.h"
#include "solver/io/memory_limits.h"
#include "solver/io/stop_request.h"

namespace galsculpt {

namespace {

std::vector<int> selectAnchorVertices(const AnchorDesc& a, const TetMesh& mesh,
                                      const std::string& file, const std::string& path) {
  std::vector<int> out;
  switch (a.shape) {
    case AnchorDesc::Shape::Box:
      for (int v = 0; v < mesh.numVertices(); ++v) {
        const Vec3& p = mesh.vertices[v];
        if ((p.array() >= a.min.array()).all() && (p.array() <= a.max.array()).all())
          out.push_back(v);
      }
      break;
    case AnchorDesc::Shape::Sphere:
      for (int v = 0; v < mesh.numVertices(); ++v) {
        if ((mesh.vertices[v] - a.center).norm() <= a.radius) out.push_back(v);
      }
      break;
    case AnchorDesc::Shape::Vertices:
      for (int v : a.vertices) {
        if (v >= mesh.numVertices()) {
          throw InputError(file, 0,
                           path + ".vertices: vertex " + std::to_string(v) +
                               " does not exist (the mesh has " +
                               std::to_string(mesh.numVertices()) + ")");
        }
        out.push_back(v);
      }
      break;
  }
  if (out.empty()) throw InputError(file, 0, path + ": selects no vertex of the mesh");
  return out;
}

}  // namespace

void checkSceneAnchors(const SceneDescription& scene, const TetMesh& mesh) {
  for (size_t i = 0; i < scene.anchors.size(); ++i)
    selectAnchorVertices(scene.anchors[i], mesh, scene.file.string(),
                         "$.anchors[" + std::to_string(i) + "]");
}

MaterialParams materialFromScene(const MaterialDesc& m, const FractureDesc& fracture) {
  MaterialParams p;
  p.compressionResists = fracture.compressionResists;
  p.crackWidth = fracture.crackWidth;
  p.model = m.model;
  p.lame = lameFromYoungPoisson(m.youngsModulus, m.poissonRatio);
  p.density = m.density;
  p.plastic = {m.yieldStress, m.hardening};
  return p;
}

namespace {

// Checked before the model is built (an exception in the initializer list).
const TetMesh& withMemoryFor(const TetMesh& mesh) {
  requireMemory(static_cast<double>(mesh.numTets()) * kSimulationBytesPerTet,
                "simulating " + std::to_string(mesh.numTets()) + " tets",
                "a mesh of fewer tets (a scene's mesh.tets, mesh import --tets) would do");
  return mesh;
}

}  // namespace

Simulation::Simulation(const SceneDescription& scene, const TetMesh& mesh, SolverChoice choice)
    : model_(buildSimModel(withMemoryFor(mesh), materialFromScene(scene.material, scene.fracture))),
      state_(initialState(model_)),
      anchors_(model_, state_),
      pieces_(scene.fracture.debrisFraction, scene.fracture.debris == DebrisRule::Remove),
      surface_(model_),
      probes_(scene.measure, mesh) {
  SolverOptions options = scene.solver;
  if (choice == SolverChoice::Reference) options.type = SolverType::Reference;
  settings_ = stepSettings(options, scene.timeStep, scene.substeps);
  model_.gravity = scene.gravity;
  model_.material.dampingMass = scene.dampingMass;
  model_.material.dampingStiffness = scene.dampingStiffness;
  for (size_t i = 0; i < scene.anchors.size(); ++i) {
    AnchorConstraint a;
    a.vertices = selectAnchorVertices(scene.anchors[i], mesh, scene.file.string(),
                                      "$.anchors[" + std::to_string(i) + "]");
    for (const PathKey& k : scene.anchors[i].path) a.path.push_back({k.time, k.offset});
    anchors_.addSceneAnchor(static_cast<int>(i), std::move(a));
  }
  for (const ColliderDesc& c : scene.colliders) {
    model_.colliders.push_back(c);  // the scene's collider is the model's, less its friction
    state_.colliders.push_back(initialColliderState(model_.colliders.back()));
    if (c.friction > 0.0 && notes_.empty())
      notes_.push_back("collider friction is not modelled yet: contacts are frictionless");
  }
  if (scene.fracture.enabled) {
    FractureSettings f;
    const FractureCriterion criterion = scene.fracture.criterion;
    f.threshold = criterion != FractureCriterion::Strain ? scene.fracture.threshold : 0.0;
    f.strainThreshold = criterion != FractureCriterion::Stress ? scene.fracture.strain : 0.0;
    f.kernelRadius = scene.fracture.kernelRadius;
    f.thresholdJitter = scene.fracture.thresholdJitter;
    f.seed = scene.fracture.seed;
    f.compressiveThreshold = scene.fracture.compressiveThreshold;
    f.criticalFraction = scene.fracture.criticalFraction;
    f.fractureEnergy = scene.fracture.energy;
    // Parts count from the debris size: a part below it would be debris once it parted.
    if (scene.fracture.partCrackedSections)
      f.partingFraction =
          scene.fracture.debrisFraction > 0.0 ? scene.fracture.debrisFraction : 0.01;
    model_.fracture = buildFractureField(model_, f);
    settings_.fractureIterations = scene.fracture.iterations;
  }
  // Cut or broken off, debris is removed by the solver too (fracture enabled or not).
  if (scene.fracture.debris == DebrisRule::Remove)
    model_.debrisRemoval = scene.fracture.debrisFraction;
  BackendChoice backend = chooseBackend(scene.solver.backend, model_, settings_);
  backend_ = std::move(backend.backend);
  if (!backend.note.empty()) notes_.push_back(backend.note);
  backendFallback_ = backend.fallback;
  applyInitialVelocity(scene.initialVelocity);
  // An exported tet mesh reopens with the cracks it was written with.
  if (std::optional<EdgeDamageState> damage = sceneMeshDamage(scene, mesh)) {
    state_.damaged = std::move(damage->damaged);
    state_.crossing = std::move(damage->crossing);
    ++state_.damageRevision;
  }
  updatePieces();
}

void Simulation::applyInitialVelocity(const InitialVelocityDesc& initial) {
  if (initial.linear.isZero() && initial.angular.isZero()) return;
  Vec3 center = Vec3::Zero();
  if (initial.center) {
    center = *initial.center;
  } else {  // the centre of mass at rest
    double mass = 0.0;
    for (int v = 0; v < model_.numVertices(); ++v) {
      center += model_.mass[v] * model_.mesh.vertices[v];
      mass += model_.mass[v];
    }
    if (mass > 0.0) center /= mass;
  }
  std::vector<char> held(model_.numVertices(), 0);
  for (const AnchorConstraint& a : state_.anchors)
    for (int v : a.vertices) held[v] = 1;
  for (int v = 0; v < model_.numVertices(); ++v) {
    if (held[v]) continue;
    state_.v[v] = initial.linear + initial.angular.cross(model_.mesh.vertices[v] - center);
  }
}

void Simulation::checkPositionsAndVelocities(const std::vector<Vec3>* x,
                                             const std::vector<Vec3>* v) const {
  for (const std::vector<Vec3>* values : {x, v}) {
    if (!values) continue;
    const std::string name = values == x ? "positions" : "velocities";
    if (values->size() != state_.x.size())
      throw std::invalid_argument(name + ": " + std::to_string(values->size()) +
                                  " rows for a model of " + std::to_string(state_.x.size()) +
                                  " vertices");
    for (size_t i = 0; i < values->size(); ++i)
      if (!(*values)[i].allFinite())
        throw std::invalid_argument(name + "[" + std::to_string(i) + "]: not a finite number");
  }
}

void Simulation::setPositionsAndVelocities(const std::vector<Vec3>* x, const std::vector<Vec3>* v) {
  checkPositionsAndVelocities(x, v);
  SimulationSnapshot s = snapshot();
  if (x) {
    s.x = *x;
    // The coarsest matrix kept between frames belongs to the old positions.
    s.solverCarry.clear();
  }
  if (v) s.v = *v;
  restore(s);
}

int Simulation::cut(const std::vector<BladeTriangle>& surface) {
  const int n = cutAlongSurface(model_, state_, surface);
  toolDamage_ += n;
  if (n > 0) updatePieces();  // volumes and exports see the new pieces before the next frame
  return n;
}

int Simulation::invertedPieces() const {
  // One piece has no surface to build for this (a closed body is never inside out as a whole).
  return pieces_.count() > 1 ? pieces_.invertedPieces(surface()) : 0;
}

double Simulation::currentVolume() const {
  return pieces_.currentVolume(model_, state_.x);
}

Simulation::PieceStats Simulation::pieceStats() {
  updatePieces();
  PieceStats p;
  p.pieces = pieces_.count();
  p.debrisPieces = pieces_.debrisPieces();
  p.debrisVolumePct = pieces_.debrisVolumePercent();
  p.debrisMassKg = pieces_.debrisMassKg();
  p.invertedPieces = invertedPieces();
  return p;
}

double Simulation::volumeChangePercent() const {
  const double rest = pieces_.restVolume();
  return rest > 0.0 ? 100.0 * (currentVolume() - rest) / rest : 0.0;
}

const VisualSurface& Simulation::surface(SurfaceUpdateStats* stats) const {
  return surface_.get(model_, state_, frame_, pieces_, stats);
}

std::vector<int> Simulation::selectVertices(const AnchorDesc& shape, const std::string& file,
                                            const std::string& jsonPath) const {
  return selectAnchorVertices(shape, model_.mesh, file, jsonPath);
}

std::vector<int> Simulation::verticesNear(const Vec3& center, double radius) const {
  std::vector<int> out;
  for (int v = 0; v < model_.numVertices(); ++v) {
    if ((state_.x[v] - center).norm() <= radius) out.push_back(v);
  }
  return out;
}

int Simulation::nearestVertex(const Vec3& point) const {
  int best = 0;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (int v = 0; v < model_.numVertices(); ++v) {
    const double d = (state_.x[v] - point).squaredNorm();
    if (d < bestDistance) {
      bestDistance = d;
      best = v;
    }
  }
  return best;
}

std::vector<double> Simulation::vertexDamage() const {
  std::vector<double> damaged(model_.numVertices(), 0.0), total(model_.numVertices(), 0.0);
  for (int e = 0; e < model_.numEdges(); ++e) {
    for (int end : model_.edges[e]) {
      total[end] += 1.0;
      damaged[end] += state_.damaged[e];
    }
  }
  for (int v = 0; v < model_.numVertices(); ++v)
    if (total[v] > 0.0) damaged[v] /= total[v];
  return damaged;
}

std::vector<double> Simulation::vertexStress() const {
  // Von Mises stress of each intact tet's elastic deformation, the largest around each vertex.
  std::vector<double> out(model_.numVertices(), 0.0);
  const MaterialParams& m = model_.material;
  for (int t = 0; t < model_.numTets(); ++t) {
    const auto& edges = model_.tetEdges[t];
    bool intact = true;
    for (int e : edges) intact = intact && !state_.damaged[e];
    if (!intact) continue;
    const Tet& tet = model_.mesh.tets[t];
    const TetPoints x{state_.x[tet[0]], state_.x[tet[1]], state_.x[tet[2]], state_.x[tet[3]]};
    Eigen::Matrix3d f = deformationGradient(model_.rest[t], x);
    if (!state_.plasticInverse.empty()) f = f * state_.plasticInverse[t];
    const double j = f.determinant();
    if (!(j > 1e-9)) continue;
    const Eigen::Matrix3d sigma = firstPiolaStress(m.model, m.lame, f) * f.transpose() / j;
    const Eigen::Matrix3d dev = sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity();
    const double vonMises = std::sqrt(1.5 * dev.squaredNorm());
    for (int v : tet) out[v] = std::max(out[v], vonMises);
  }
  return out;
}

std::size_t SimulationSnapshot::bytes() const {
  std::size_t anchorBytes = 0;
  for (const AnchorConstraint& a : anchors)
    anchorBytes += a.vertices.size() * sizeof(int) + a.origin.size() * sizeof(Vec3) +
                   a.path.size() * sizeof(AnchorKey);
  return (x.size() + v.size()) * sizeof(Vec3) + damaged.size() + crossing.size() * sizeof(float) +
         plasticInverse.size() * sizeof(Eigen::Matrix3d) + plasticStrain.size() * sizeof(double) +
         colliders.size() * sizeof(ColliderState) + solverCarry.size() * sizeof(double) +
         anchorBytes + sizeof(*this);
}

SimulationSnapshot Simulation::snapshot() const {
  SimulationSnapshot s;
  s.solverCarry = backend_->carriedState();
  s.x = state_.x;
  s.v = state_.v;
  s.damaged = state_.damaged;
  s.crossing = state_.crossing;
  s.plasticInverse = state_.plasticInverse;
  s.plasticStrain = state_.plasticStrain;
  s.colliders = state_.colliders;
  s.time = state_.time;
  s.frame = frame_;
  s.anchors = state_.anchors;
  s.anchorTags = anchors_.tags();
  s.nextAnchorId = anchors_.nextId();
  s.letGo = state_.letGo;
  s.toolDamage = toolDamage_;
  return s;
}

void Simulation::restore(const SimulationSnapshot& s) {
  if (s.x.size() != state_.x.size() || s.v.size() != state_.v.size() ||
      s.damaged.size() != state_.damaged.size() || s.crossing.size() != state_.crossing.size() ||
      s.plasticInverse.size() != state_.plasticInverse.size() ||
      s.plasticStrain.size() != state_.plasticStrain.size() ||
      s.colliders.size() != state_.colliders.size() || s.anchors.size() != s.anchorTags.size())
    throw std::invalid_argument(
        "the saved state does not fit this model (" + std::to_string(s.x.size()) + " vertices, " +
        std::to_string(s.damaged.size()) + " edges, " +
        (s.plasticInverse.empty() ? "elastic" : "plastic") + "; the model has " +
        std::to_string(state_.x.size()) + ", " + std::to_string(state_.damaged.size()) + ", " +
        (state_.plasticInverse.empty() ? "elastic" : "plastic") + ")");
  state_.x = s.x;
  state_.v = s.v;
  // No NaN is ever stored in crossings, so == compares them exactly.
  if (state_.damaged != s.damaged || state_.crossing != s.crossing) {
    state_.damaged = s.damaged;
    state_.crossing = s.crossing;
    ++state_.damageRevision;
  }
  state_.plasticInverse = s.plasticInverse;
  state_.plasticStrain = s.plasticStrain;
  state_.colliders = s.colliders;
  state_.time = s.time;
  frame_ = s.frame;
  state_.anchors = s.anchors;
  anchors_.restore(s.anchorTags, s.nextAnchorId);
  state_.letGo = s.letGo;
  toolDamage_ = s.toolDamage;
  surface_.invalidate();  // positions changed without a frame
  ++generation_;
  backend_->adoptCarriedState(s.solverCarry);
  updatePieces();
}

namespace {

bool allFinite(const std::vector<Vec3>& values) {
  for (const Vec3& p : values)
    if (!p.allFinite()) return false;
  return true;
}

}  // namespace

FrameMetrics Simulation::advance() {
  const auto start = std::chrono::steady_clock::now();
  // Kept to undo a frame that diverges: no NaN reaches the window, an export or the metrics.
  lastFinite_.first.assign(state_.x.begin(), state_.x.end());
  lastFinite_.second.assign(state_.v.begin(), state_.v.end());
  // And the rest of the state, to leave nothing of a frame a stop cuts short. A frame of one
  // sub-step with no fracture pass is rolled back by the solver itself (its sub-step's start is
  // the frame's start); only more sub-steps or a fracture pass leave damage and plastic shapes
  // to bring back.
  frameStart_.time = state_.time;
  frameStart_.colliders = state_.colliders;
  frameStart_.damageRevision = state_.damageRevision;
  frameStart_.whole = settings_.substeps > 1 || model_.fracture.enabled;
  if (frameStart_.whole) {
    frameStart_.damaged.assign(state_.damaged.begin(), state_.damaged.end());
    frameStart_.crossing.assign(state_.crossing.begin(), state_.crossing.end());
    frameStart_.plasticInverse.assign(state_.plasticInverse.begin(), state_.plasticInverse.end());
    frameStart_.plasticStrain.assign(state_.plasticStrain.begin(), state_.plasticStrain.end());
  }
  StepReport r;
  try {
    r = backend_->step(state_, settings_);
  } catch (const std::exception& e) {
    // A device failure (lost GPU, out of memory) throws before the state is written back: the
    // frame runs again on the CPU, and so does the rest of the session.
    if (!backend_->offloads()) throw;
    notes_.push_back("the " + backend_->name() + " backend failed (" + e.what() +
                     "): running on the CPU from frame " + std::to_string(frame_));
    backend_ = std::make_unique<CpuStepBackend>(model_);
    r = backend_->step(state_, settings_);
  }
  if (r.stopped) {
    // Ctrl-C or SIGTERM within the frame: back to the last whole frame, then the stop.
    std::copy(lastFinite_.first.begin(), lastFinite_.first.end(), state_.x.begin());
    std::copy(lastFinite_.second.begin(), lastFinite_.second.end(), state_.v.begin());
    state_.time = frameStart_.time;
    state_.colliders = frameStart_.colliders;
    if (frameStart_.whole) {
      state_.plasticInverse = frameStart_.plasticInverse;
      state_.plasticStrain = frameStart_.plasticStrain;
    }
    if (frameStart_.whole && state_.damageRevision != frameStart_.damageRevision) {
      state_.damaged = frameStart_.damaged;
      state_.crossing = frameStart_.crossing;
      ++state_.damageRevision;  // a new revision: whatever saw the frame's damage looks again
      updatePieces();
    }
    surface_.invalidate();
    throw Interrupted(stopSignal());
  }
  const bool diverged = !allFinite(state_.x) || !allFinite(state_.v);
  if (diverged) {
    // The body stays where the last finite frame left it, at rest; the frame is reported as
    // not converged, with a warning and a note.
    std::copy(lastFinite_.first.begin(), lastFinite_.first.end(), state_.x.begin());
    std::fill(state_.v.begin(), state_.v.end(), Vec3::Zero());
    r.converged = false;
    if (++divergedFrames_ <= kDivergenceNotes)
      notes_.push_back("frame " + std::to_string(frame_ + 1) +
                       " diverged (positions not finite): the body was kept where frame " +
                       std::to_string(frame_) + " left it, at rest");
  }
  if (!std::isfinite(r.residual)) r.residual = -1.0;
  if (!std::isfinite(r.pieceResidual)) r.pieceResidual = -1.0;
  if (!std::isfinite(r.elasticEnergy)) r.elasticEnergy = -1.0;
  ++frame_;
  ++generation_;
  FrameMetrics m;
  m.frame = frame_;
  m.timeS = state_.time;
  static_cast<FrameStatistics&>(m) = r;  // the solver's figures, as the frame reported them
  m.warnings =
      r.retries + (r.converged ? 0 : 1) + (r.invertedElements > 0 ? 1 : 0) + (diverged ? 1 : 0);
  Vec3 contact = Vec3::Zero();
  for (const Vec3& f : r.contactForces) contact += f;
  m.contactForceN = contact.norm();
  m.newlyDamaged += toolDamage_;  // edges broken this frame: fracture and tools
  probes_.read(model_, state_, anchors_, r.contactForces, m);
  toolDamage_ = 0;
  updatePieces();
  m.pieces = pieces_.count();
  m.volume = currentVolume();
  m.debrisPieces = pieces_.debrisPieces();
  m.debrisVolumePct = pieces_.debrisVolumePercent();
  m.debrisMassKg = pieces_.debrisMassKg();
  const double rest = pieces_.restVolume();
  m.volumeChangePct = rest > 0.0 ? 100.0 * (m.volume - rest) / rest : 0.0;
  for (int v = 0; v < model_.numVertices(); ++v) {
    m.kineticEnergy += 0.5 * model_.mass[v] * state_.v[v].squaredNorm();
    m.maxDisplacement = std::max(m.maxDisplacement, (state_.x[v] - model_.mesh.vertices[v]).norm());
  }
  for (std::uint8_t d : state_.damaged) m.damagedEdges += d;
  m.msTotal = msSince(start);
  m.msOther = std::max(0.0, m.msTotal - m.msElements - m.msSolve - m.msPlastic - m.msFracture);
  // Outside the frame's time, as exports are: it brings the visualization surface up to date
  // (the window does so to draw the frame anyway; on the fractured Charpy bar about 5 ms).
  m.invertedPieces = invertedPieces();
  return m;
}

}  // namespace galsculpt
