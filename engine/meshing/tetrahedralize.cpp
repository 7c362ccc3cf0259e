#include "engine/meshing/tetrahedralize.h"

#include <stdlib.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>

#include "engine/meshing/subprocess.h"
#include "engine/surface/solidify.h"
#include "engine/surface/surface_bvh.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/memory_limits.h"
#include "solver/io/tetgen_io.h"
#include "solver/mesh/surface_checks.h"
#include "solver/mesh/surface_parts.h"
#include "solver/mesh/surface_simplify.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "galsculpt-tetgen-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary directory");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void writeSmesh(const fs::path& path, const TriMesh& surface) {
  writeFileAtomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    out << surface.numVertices() << " 3 0 0\n";
    for (int i = 0; i < surface.numVertices(); ++i) {
      const Vec3& p = surface.vertices[i];
      out << i << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    out << surface.numFaces() << " 0\n";
    for (const Tri& f : surface.faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
    out << "0\n0\n";
  });
}

// Reads the tet count from the .ele header without parsing the whole file.
long long countTets(const fs::path& ele) {
  std::ifstream in(ele);
  long long n = -1;
  in >> n;
  return n;
}

// Strictest first: TetGen's quality bound with Steiner points allowed on the surface, then the
// surface kept as given (-Y) with looser bounds, and last no quality bound at all.
std::vector<TetQuality> qualityLevels(double radiusEdgeRatio) {
  return {{radiusEdgeRatio, false}, {radiusEdgeRatio, true}, {2.0, true}, {4.0, true}, {0.0, true}};
}

std::string tetgenSwitches(const TetQuality& q, double bound) {
  std::ostringstream sw;
  sw << "-p";
  if (q.keepSurface) sw << "Y";
  if (q.radiusEdgeRatio > 0.0) sw << "q" << q.radiusEdgeRatio;
  if (bound > 0.0) sw << "a" << std::setprecision(9) << bound;
  sw << "Q";
  return sw.str();
}

constexpr double kTetsPerSurfaceFace = 12.0;

// How far a simplified surface strays from the original: its enclosed volume's relative change,
// and the farthest distance between the two (each one's vertices and face centres measured to
// the other: a sampled two-sided Hausdorff distance) relative to the original's bounding-box
// diagonal.
struct ShapeChange {
  double volume = 0.0, distance = 0.0;
};
ShapeChange shapeChange(const TriMesh& original, const TriMesh& simplified) {
  ShapeChange change;
  const double volume = std::abs(enclosedVolume(original));
  change.volume = volume > 0.0 ? std::abs(enclosedVolume(simplified)) / volume - 1.0 : 0.0;
  const double diagonal = std::max(boundingBox(original.vertices).size().norm(), 1e-300);
  double farthest = 0.0;
  for (const auto& [from, to] : {std::pair{&original, &simplified}, {&simplified, &original}}) {
    SurfaceBvh bvh;
    bvh.build(*to);
    for (const Vec3& v : from->vertices) farthest = std::max(farthest, bvh.distance(*to, v));
    for (const Tri& f : from->faces) {
      const Vec3 centre =
          (from->vertices[f[0]] + from->vertices[f[1]] + from->vertices[f[2]]) / 3.0;
      farthest = std::max(farthest, bvh.distance(*to, centre));
    }
  }
  change.distance = farthest / diagonal;
  return change;
}

std::string percent(double fraction) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << 100.0 * fraction << " %";
  return s.str();
}

// A simplified copy with about `faces` faces that is still closed, free of crossings and within
// kShapeVolume / kShapeDistance of the original's shape; more faces where fewer stray too far;
// none when no simplification keeps the shape.
std::optional<TriMesh> simplifyForMeshing(const TriMesh& surface, int faces,
                                          const TetrahedralizeOptions& options) {
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  for (int attempt = 0; attempt < 8 && faces < surface.numFaces();
       ++attempt, faces = faces * 3 / 2) {
    say("simplifying " + options.surfaceName + " (" + std::to_string(surface.numFaces()) +
        " faces) towards " + std::to_string(std::max(faces, 100)) + " faces");
    TriMesh coarse = simplifySurface(surface, std::max(faces, 100));
    if (!analyzeSurface(coarse).closedManifold() || !findSelfIntersections(coarse, 1).empty())
      continue;
    if (!options.keepShape) {
      say("simplified " + options.surfaceName + " from " + std::to_string(surface.numFaces()) +
          " to " + std::to_string(coarse.numFaces()) + " faces");
      return coarse;
    }
    const ShapeChange change = shapeChange(surface, coarse);
    const std::string what = std::to_string(coarse.numFaces()) + " faces (volume " +
                             (change.volume >= 0.0 ? "+" : "") + percent(change.volume) +
                             ", farthest " + percent(change.distance) + " of its size)";
    if (std::abs(change.volume) <= kShapeVolume && change.distance <= kShapeDistance) {
      say("simplified " + options.surfaceName + " from " + std::to_string(surface.numFaces()) +
          " to " + what + "; " + std::to_string(surface.numFaces() - coarse.numFaces()) +
          " faces dropped");
      return coarse;
    }
    say("simplified to " + what + ": beyond " + percent(kShapeVolume) + " of its volume or " +
        percent(kShapeDistance) + " of its size, keeping more faces");
  }
  say("no simplification of " + options.surfaceName + " keeps its shape within " +
      percent(kShapeVolume) + " of its volume and " + percent(kShapeDistance) +
      " of its size: meshing it as given");
  return std::nullopt;
}

// TetGen runs on one surface in a temporary folder: each run's tet count, the closest so far,
// and the mesh of the last run when it is accepted.
class TetgenRuns {
 public:
  TetgenRuns(const TriMesh& surface, const TetrahedralizeOptions& options)
      : options_(options), smesh_(dir_.path() / "input.smesh") {
    writeSmesh(smesh_, surface);
  }
  // Replaces the surface (a simplified copy); later runs mesh it.
  void setSurface(const TriMesh& surface) {
    smesh_ = dir_.path() / "simplified.smesh";
    writeSmesh(smesh_, surface);
  }
  int attempts() const { return attempts_; }

  // One TetGen run; returns its tet count. `bound` <= 0 means no volume bound.
  long long run(const TetQuality& q, double bound) {
    const std::string sw = tetgenSwitches(q, bound);
    const fs::path log = dir_.path() / "tetgen.log";
    const SubprocessResult r =
        runSubprocess({options_.program, sw, smesh_.string()}, options_.timeoutSeconds, log);
    if (!r.started) {
      throw std::runtime_error("cannot run '" + options_.program +
                               "': is TetGen installed? (scripts/install-deps.sh installs it)");
    }
    if (!r.succeeded()) {
      // TetGen says "Out of memory." and throws an int when an allocation fails.
      const bool memory = r.logTail.find("Out of memory") != std::string::npos ||
                          r.logTail.find("bad_alloc") != std::string::npos;
      throw std::runtime_error(
          "tetgen " + (memory ? "ran out of memory (" + r.describe() + ")" : r.describe()) +
          " on " + options_.surfaceName + " (switches " + sw + ")" +
          (memory ? availableMemoryText() + ": ask for fewer tets (--tets)" : "") +
          (r.logTail.empty() ? "" : ":\n" + r.logTail));
    }
    const long long count = countTets(fs::path(resultStem()).concat(".ele"));
    if (count <= 0) throw std::runtime_error("tetgen wrote no tets for " + options_.surfaceName);
    ++attempts_;
    if (options_.progress) {
      std::ostringstream line;
      line << "tetgen attempt " << attempts_ << " of at most " << options_.maxAttempts << " (" << sw
           << "): " << count << " tets (target " << options_.targetTets << ")";
      options_.progress(line.str());
    }
    const double target = options_.targetTets;
    if (bestCount_ < 0 || std::abs(count / target - 1.0) < std::abs(bestCount_ / target - 1.0)) {
      bestCount_ = count;
      bestSwitches_ = sw;
    }
    return count;
  }

  // The last run's mesh, as the result.
  TetrahedralizeResult accept(const TetQuality& q, double bound) const {
    TetrahedralizeResult result;
    result.mesh = readTetGen(resultStem());
    result.mesh.faces.clear();
    result.mesh.faceMarkers.clear();
    result.mesh.vertexMarkers.clear();
    result.volumeBound = bound;
    result.quality = q;
    result.attempts = attempts_;
    return result;
  }

  [[noreturn]] void fail() const {
    std::ostringstream msg;
    msg << "could not reach " << options_.targetTets << " tets within "
        << static_cast<int>(options_.tolerance * 100) << " % for " << options_.surfaceName << " in "
        << attempts_ << " TetGen runs: closest was " << bestCount_ << " tets (" << bestSwitches_
        << ")";
    if (bestCount_ > options_.targetTets) {
      msg << "; the surface is finer than " << options_.targetTets << " tets allow (--tets "
          << bestCount_ << " or more would do)";
    }
    throw TetCountUnreachable(msg.str(), bestCount_);
  }

 private:
  // TetGen writes its result beside its input: input.smesh -> input.1.node / .ele.
  fs::path resultStem() const { return fs::path(smesh_).replace_extension(".1"); }

  const TetrahedralizeOptions& options_;
  TempDir dir_;
  fs::path smesh_;
  int attempts_ = 0;
  long long bestCount_ = -1;
  std::string bestSwitches_;
};

// Searches the volume bound that gives the target tet count at one quality level, from the
// count with no bound (`fewest`); none when the attempts run out first.
std::optional<TetrahedralizeResult> searchVolumeBound(TetgenRuns& runs, const TetQuality& level,
                                                      double volume,
                                                      const TetrahedralizeOptions& options) {
  const double target = options.targetTets;
  TetQuality q = level;
  int nudges = 0;
  double bound = 1.5 * volume / target;     // a quality mesh has ~1.5x volume / bound tets
  double lowBound = 0.0, lowCount = 0.0;    // gave too many tets
  double highBound = 0.0, highCount = 0.0;  // gave too few tets
  while (runs.attempts() < options.maxAttempts) {
    const long long count = runs.run(q, bound);
    if (std::abs(count / target - 1.0) <= options.tolerance) return runs.accept(q, bound);
    if (count > target) {
      lowBound = bound;
      lowCount = static_cast<double>(count);
    } else {
      highBound = bound;
      highCount = static_cast<double>(count);
    }
    if (lowBound > 0.0 && highBound > 0.0 && highBound < 1.01 * lowBound) {
      // The count jumps across the target within a 1 % change of the bound (TetGen's
      // refinement is discontinuous): nudge the quality bound and search again.
      if (q.radiusEdgeRatio > 0.0) q.radiusEdgeRatio *= (nudges++ % 2 == 0) ? 1.04 : 1.0 / 1.08;
      lowBound = highBound = 0.0;
    }
    if (lowBound > 0.0 && highBound > 0.0) {
      // Interpolate log(count) linearly in log(bound) between the bracket ends.
      const double t =
          std::clamp(std::log(lowCount / target) / std::log(lowCount / highCount), 0.2, 0.8);
      bound = std::exp(std::log(lowBound) + t * (std::log(highBound) - std::log(lowBound)));
    } else {
      bound *= std::clamp(count / target, 1.0 / 64.0, 64.0);
    }
  }
  return std::nullopt;
}

}  // namespace

void checkMeshableSurface(const TriMesh& surface, const std::string& name, bool crossings) {
  if (surface.faces.empty()) throw InputError(name, 0, "the surface has no triangles");
  const SurfaceTopology topo = analyzeSurface(surface);
  if (!topo.closedManifold()) {
    throw InputError(name, 0, "cannot tetrahedralize: the surface is " + topo.describeProblem());
  }
  if (!crossings) return;
  const auto pairs = findSelfIntersections(surface, 1000);
  if (!pairs.empty()) {
    throw InputError(name, 0,
                     "cannot tetrahedralize: the surface is self-intersecting: faces " +
                         std::to_string(pairs[0].first) + " and " +
                         std::to_string(pairs[0].second) + " cross (" +
                         std::to_string(pairs.size()) + (pairs.size() >= 1000 ? "+" : "") +
                         " crossing pair(s))");
  }
}

namespace {

// TetGen's runs on a closed surface free of crossings, towards the target count.
TetrahedralizeResult tetrahedralizeClean(const TriMesh& input,
                                         const TetrahedralizeOptions& options) {
  TriMesh surface = input;
  double volume = enclosedVolume(surface);
  if (volume < 0.0) {  // inside-out: flip, the solid is the same
    for (Tri& f : surface.faces) std::swap(f[1], f[2]);
    volume = -volume;
  }
  TetgenRuns runs(surface, options);
  const double target = options.targetTets;
  bool simplified = false;
  const std::vector<TetQuality> levels = qualityLevels(options.radiusEdgeRatio);
  for (size_t li = 0; li < levels.size(); ++li) {
    const TetQuality& level = levels[li];
    // With the surface kept as given TetGen still needs about 3 tets per surface face: a surface
    // with more faces than that allows is simplified before any run.
    const bool hopeless = surface.numFaces() * 3.0 > target * (1.0 + options.tolerance);
    if ((li == 2 || (li == 0 && hopeless)) && !simplified) {
      // The surface as given forces too many tets even when kept as is: simplify it to about
      // one face per kTetsPerSurfaceFace tets and start over with the strict levels.
      simplified = true;
      const int faces = static_cast<int>(target / kTetsPerSurfaceFace);
      if (surface.numFaces() > faces) {
        if (auto coarse = simplifyForMeshing(surface, faces, options)) {
          surface = std::move(*coarse);
          runs.setSurface(surface);
          li = static_cast<size_t>(-1);  // restart at the strictest level
          continue;
        }
      }
    }
    // The fewest tets this quality allows: with no volume bound, only the surface and the
    // quality bound place points. A surface finer than the target needs relaxes the quality.
    const long long fewest = runs.run(level, 0.0);
    if (fewest > target * (1.0 + options.tolerance)) continue;
    if (fewest >= target * (1.0 - options.tolerance)) return runs.accept(level, 0.0);
    if (auto result = searchVolumeBound(runs, level, volume, options)) return *result;
    break;
  }
  runs.fail();
}

// A shell that crosses itself, remade as the region it encloses (solidify.h) on a grid of its
// median edge (what an export does with a folded piece).
TriMesh solidifiedShell(const TriMesh& shell) {
  std::vector<double> edges;
  for (const Tri& f : shell.faces)
    for (int k = 0; k < 3; ++k)
      edges.push_back((shell.vertices[f[k]] - shell.vertices[f[(k + 1) % 3]]).norm());
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
  return solidify(shell, {.cell = edges[edges.size() / 2]});
}

}  // namespace

TetrahedralizeResult tetrahedralize(const TriMesh& input, const TetrahedralizeOptions& options) {
  checkMeshableSurface(input, options.surfaceName, !options.solidifyCrossings);
  if (options.targetTets < 1) throw std::invalid_argument("target tet count must be positive");
  checkMemoryForTets(options.targetTets, options.surfaceName);
  if (!options.solidifyCrossings) return tetrahedralizeClean(input, options);
  TriMesh surface = input;
  if (enclosedVolume(surface) < 0.0)  // inside-out: the same solid, faces turned
    for (Tri& f : surface.faces) std::swap(f[1], f[2]);
  constexpr size_t kAllPairs = 100000000;
  std::vector<std::pair<int, int>> crossings = findSelfIntersections(surface, kAllPairs);
  if (crossings.empty()) return tetrahedralizeClean(surface, options);
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };

  // Shells that cross themselves are remade as the region they enclose.
  std::vector<int> shellOfFace;
  const int shells = countSurfacePieces(surface, &shellOfFace);
  std::vector<char> selfCrossing(shells, 0);
  for (const auto& [f, g] : crossings)
    if (shellOfFace[f] == shellOfFace[g]) selfCrossing[shellOfFace[f]] = 1;
  TriMesh items;  // every shell, the self-crossing ones remade; itemOfFace numbers them
  std::vector<int> itemOfFace;
  double volumeBefore = 0.0, volumeAfter = 0.0;
  int remade = 0, remadeShells = 0;
  for (int s = 0; s < shells; ++s) {
    TriMesh shell = facesOfGroup(surface, shellOfFace, s);
    if (selfCrossing[s]) {
      volumeBefore += enclosedVolume(shell);
      shell = solidifiedShell(shell);
      volumeAfter += enclosedVolume(shell);
      ++remade;
      remadeShells += countSurfacePieces(shell);
    }
    appendSurface(items, shell);
    itemOfFace.resize(items.faces.size(), s);
  }
  if (remade > 0) {
    std::ostringstream line;
    line << options.surfaceName << ": " << remade
         << " shell(s) crossing themselves remade as the region they enclose (" << remadeShells
         << " shell(s) where the grid parts thin necks, volume " << volumeBefore << " -> "
         << volumeAfter << " m^3)";
    say(line.str());
  }
  crossings = findSelfIntersections(items, kAllPairs);
  if (crossings.empty()) return tetrahedralizeClean(items, options);

  // Shells through each other (pieces of an export that overlap): meshed in groups of shells
  // that do not cross, each group its share of the tets by volume; the overlaps stay as given.
  std::vector<std::vector<int>> touching(shells);
  for (const auto& [f, g] : crossings) {
    const int a = itemOfFace[f], b = itemOfFace[g];
    if (a == b) continue;  // cannot happen after the remaking; TetGen says if it does
    touching[a].push_back(b);
    touching[b].push_back(a);
  }
  std::vector<int> colour(shells, -1);
  int colours = 0;
  for (int s = 0; s < shells; ++s) {
    std::vector<char> used(colours + 1, 0);
    for (int t : touching[s])
      if (colour[t] >= 0) used[colour[t]] = 1;
    colour[s] = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
    colours = std::max(colours, colour[s] + 1);
  }
  std::vector<int> groupOfFace(items.faces.size());
  for (size_t f = 0; f < groupOfFace.size(); ++f) groupOfFace[f] = colour[itemOfFace[f]];
  const std::vector<TriMesh> groups = splitByGroup(items, groupOfFace, colours);
  double total = 0.0;
  for (const TriMesh& group : groups) total += enclosedVolume(group);
  {
    std::ostringstream line;
    line << options.surfaceName << ": " << shells << " shell(s), some through each other ("
         << crossings.size() << " crossing face pair(s) between shells): meshed in " << colours
         << " groups of shells that do not cross, the overlaps kept as they are";
    say(line.str());
  }
  TetrahedralizeResult merged;
  // A group whose share is below what its surface allows (a crumb in contact with a body) is
  // meshed as coarse as its surface lets it; the whole must still land within the tolerance.
  long long extra = 0;
  for (int c = 0; c < colours; ++c) {
    TetrahedralizeOptions part = options;
    const double share = enclosedVolume(groups[c]) / total;
    part.targetTets = std::max(1, static_cast<int>(std::lround(share * options.targetTets)));
    part.surfaceName = options.surfaceName + " (group " + std::to_string(c + 1) + " of " +
                       std::to_string(colours) + ")";
    TetrahedralizeResult result;
    try {
      try {
        result = tetrahedralizeClean(groups[c], part);
      } catch (const TetCountUnreachable& e) {
        if (e.closest <= part.targetTets) throw;
        TetrahedralizeOptions coarsest = part;
        coarsest.targetTets = e.closest;
        result = tetrahedralizeClean(groups[c], coarsest);
        extra += result.mesh.numTets() - part.targetTets;
        say(part.surfaceName + ": its share of " + std::to_string(part.targetTets) +
            " tets is finer than its surface allows: meshed with " +
            std::to_string(result.mesh.numTets()));
        if (std::abs(static_cast<double>(extra)) > options.tolerance * options.targetTets)
          throw TetCountUnreachable(part.surfaceName + " needs " +
                                        std::to_string(result.mesh.numTets()) + " tets, not its " +
                                        std::to_string(part.targetTets),
                                    result.mesh.numTets());
      }
    } catch (const TetCountUnreachable& e) {
      // The group's count scaled to the whole: each group gets its share of what is asked.
      const long long whole = static_cast<long long>(
          std::ceil(static_cast<double>(e.closest) * options.targetTets / part.targetTets));
      throw TetCountUnreachable(std::string(e.what()) + "; for the whole of " +
                                    options.surfaceName + ", --tets " + std::to_string(whole) +
                                    " or more would give this group its share",
                                static_cast<int>(std::min<long long>(whole, INT_MAX)));
    }
    const int base = merged.mesh.numVertices();
    merged.mesh.vertices.insert(merged.mesh.vertices.end(), result.mesh.vertices.begin(),
                                result.mesh.vertices.end());
    for (Tet t : result.mesh.tets) {
      for (int& v : t) v += base;
      merged.mesh.tets.push_back(t);
    }
    merged.attempts += result.attempts;
    merged.quality = result.quality;
    merged.volumeBound = std::max(merged.volumeBound, result.volumeBound);
  }
  return merged;
}

TetrahedralizeResult tetrahedralizeAny(const std::vector<TriMesh>& surfaces,
                                       const TetrahedralizeOptions& options) {
  if (surfaces.empty()) throw std::invalid_argument("no surface to tetrahedralize");
  std::optional<TetCountUnreachable> nearest;
  for (const TriMesh& surface : surfaces) {
    try {
      return tetrahedralize(surface, options);
    } catch (const TetCountUnreachable& e) {
      if (!nearest || std::abs(e.closest - options.targetTets) <
                          std::abs(nearest->closest - options.targetTets))
        nearest = e;
      if (options.progress && &surface != &surfaces.back())
        options.progress("trying a finer surface of " + options.surfaceName);
    }
  }
  throw *nearest;
}

void checkMemoryForTets(long long tets, const std::string& name) {
  requireMemory(static_cast<double>(tets) * kTetgenBytesPerTet,
                "meshing " + name + " to " + std::to_string(tets) + " tets (TetGen)",
                "ask for fewer tets");
}

}  // namespace galsculpt
