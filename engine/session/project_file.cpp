#include "engine/session/project_file.h"

#include <bit>
#include <cstring>
#include <fstream>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[] = "GALSCULPT PROJECT";
static_assert(std::endian::native == std::endian::little, "project files are little-endian");

template <typename T>
void writeArray(std::ostream& out, const std::vector<T>& values) {
  out.write(reinterpret_cast<const char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(T)));
}

// Reads binary arrays with the file name and byte offset in every error.
class BinaryReader {
 public:
  BinaryReader(std::string data, std::size_t offset, std::string file)
      : data_(std::move(data)), offset_(offset), file_(std::move(file)) {}
  template <typename T>
  void read(std::vector<T>& out, std::size_t count, const char* what) {
    const std::size_t bytes = count * sizeof(T);
    if (data_.size() - offset_ < bytes)
      throw InputError(file_ + ": truncated at byte " + std::to_string(data_.size()) + ": " + what +
                       " needs " + std::to_string(bytes) + " bytes from byte " +
                       std::to_string(offset_));
    out.resize(count);
    std::memcpy(out.data(), data_.data() + offset_, bytes);
    offset_ += bytes;
  }
  std::size_t offset() const { return offset_; }
  bool atEnd() const { return offset_ == data_.size(); }

 private:
  std::string data_;
  std::size_t offset_;
  std::string file_;
};

Vec3 readVec(JsonObject& o, const std::string& key) {
  if (!o.has(key)) o.fail(key, "is required");
  return o.vec3(key, Vec3::Zero());
}

std::vector<double> flat(const std::vector<Vec3>& v) {
  std::vector<double> out(3 * v.size());
  for (size_t i = 0; i < v.size(); ++i)
    for (int k = 0; k < 3; ++k) out[3 * i + k] = v[i][k];
  return out;
}

std::vector<Vec3> unflat(const std::vector<double>& d) {
  std::vector<Vec3> out(d.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = Vec3(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
  return out;
}

void checkFinite(const std::vector<double>& values, const std::string& file, const char* what) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw InputError(file + ": " + what + ": value " + std::to_string(i) + " is not finite");
}

}  // namespace

void writeProject(const fs::path& file, const SceneDescription& scene, const Simulation& sim,
                  const std::vector<ToolEvent>& recording,
                  const std::optional<CameraPose>& camera) {
  const SimModel& model = sim.model();
  const SimulationSnapshot state = sim.snapshot();
  nlohmann::json h;
  h["scene"] = scene.source;
  h["scene_file"] = scene.file.generic_string();
  h["frame"] = state.frame;
  h["time"] = state.time;
  nlohmann::json colliders = nlohmann::json::array();
  for (const ColliderState& c : state.colliders)
    colliders.push_back({{"angle", c.angle}, {"angular_velocity", c.angularVelocity}});
  h["colliders"] = colliders;
  h["vertices"] = model.numVertices();
  h["tets"] = model.numTets();
  h["edges"] = model.numEdges();
  h["plastic"] = !state.plasticInverse.empty();
  h["tool_damage"] = state.toolDamage;
  h["solver_carry"] = state.solverCarry.size();
  h["next_anchor_id"] = state.nextAnchorId;
  if (state.letGo) h["let_go"] = true;  // (SimState::letGo; files without it: false)
  nlohmann::json anchors = nlohmann::json::array();
  for (size_t i = 0; i < state.anchors.size(); ++i) {
    const AnchorConstraint& a = state.anchors[i];
    nlohmann::json j;
    const AnchorTag& tag = state.anchorTags[i];
    j["id"] = tag.id;
    if (tag.releaseFrame >= 0) j["release_frame"] = tag.releaseFrame;
    if (!tag.name.empty()) j["name"] = tag.name;
    j["vertices"] = a.vertices;
    nlohmann::json origin = nlohmann::json::array(), path = nlohmann::json::array();
    for (const Vec3& p : a.origin) origin.push_back(vec3Json(p));
    for (const AnchorKey& k : a.path)
      path.push_back({{"time", k.time}, {"offset", vec3Json(k.offset)}});
    j["origin"] = origin;
    j["path"] = path;
    if (!a.springWeights.empty()) j["spring_weights"] = a.springWeights;
    anchors.push_back(j);
  }
  h["anchors"] = anchors;
  nlohmann::json events = nlohmann::json::array();
  for (const ToolEvent& e : recording) events.push_back(toolEventJson(e));
  h["recording"] = events;
  if (camera) h["camera"] = cameraPoseJson(*camera);
  const std::string header = h.dump();

  std::vector<int> tets;
  tets.reserve(4 * model.mesh.tets.size());
  for (const Tet& t : model.mesh.tets) tets.insert(tets.end(), t.begin(), t.end());
  std::vector<double> plastic;
  for (const Eigen::Matrix3d& m : state.plasticInverse)
    plastic.insert(plastic.end(), m.data(), m.data() + 9);
  writeFileDurably(file, [&](std::ostream& out) {
    out << kMagic << ' ' << kProjectVersion << '\n' << header.size() << '\n' << header;
    writeArray(out, flat(model.mesh.vertices));
    writeArray(out, tets);
    writeArray(out, flat(state.x));
    writeArray(out, flat(state.v));
    writeArray(out, state.damaged);
    writeArray(out, state.crossing);
    if (!state.plasticInverse.empty()) {
      writeArray(out, plastic);
      writeArray(out, state.plasticStrain);
    }
    writeArray(out, state.solverCarry);
  });
}

void writeProject(const fs::path& file, const SculptSession& session,
                  const std::optional<CameraPose>& camera) {
  writeProject(file, session.scene(), session.simulation(), session.recordingSoFar(), camera);
}

std::unique_ptr<SculptSession> sessionFromProject(const Project& project, const fs::path& file) {
  std::unique_ptr<SculptSession> session;
  try {
    session = std::make_unique<SculptSession>(project.scene, project.mesh);
    session->load(project.state, project.recording);
  } catch (const std::invalid_argument& e) {
    throw InputError(file.string() + ": " + e.what());
  }
  return session;
}

bool looksLikeProject(const fs::path& file) {
  if (!isRegularFile(file)) return false;  // a pipe would block here; its reader refuses it
  std::ifstream in(file, std::ios::binary);
  char buffer[sizeof(kMagic) - 1] = {};
  in.read(buffer, sizeof(buffer));
  return in && std::memcmp(buffer, kMagic, sizeof(buffer)) == 0;
}

namespace {

// Line 1 of a project: the magic and a whole-number version this build reads. Returns the
// version; `line1` is where that line ends.
int readProjectVersion(const std::string& data, const std::string& name, std::size_t& line1) {
  // Line 1: magic and version; line 2: header length; then the header.
  line1 = data.find('\n');
  if (data.rfind(kMagic, 0) != 0 || line1 == std::string::npos)
    throw InputError(
        name, 1,
        "not a Galsculpt project (it must start with '" + std::string(kMagic) + " <version>')");
  // The whole rest of line 1 is the version: digits only ("1garbage" and "1.9" are not 1).
  const std::string versionText =
      line1 > sizeof(kMagic) ? data.substr(sizeof(kMagic), line1 - sizeof(kMagic)) : "";
  if (data[sizeof(kMagic) - 1] != ' ' || versionText.empty() || versionText.size() > 9 ||
      versionText.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(name, 1,
                     "the format version is not a whole number ('" + std::string(kMagic) +
                         " <version>' expected)");
  const int version = std::stoi(versionText);
  if (version < 1) throw InputError(name, 1, "bad format version " + std::to_string(version));
  if (version > kProjectVersion)
    throw InputError(name, 1,
                     "made by a newer Galsculpt (format version " + std::to_string(version) +
                         "; this one reads up to " + std::to_string(kProjectVersion) + ")");
  return version;
}

// One anchor of the header's "anchors" list (its id, release frame and name into `tag`),
// checked against the mesh.
AnchorConstraint readAnchor(const nlohmann::json& json, const std::string& where, int nv,
                            const std::string& name, AnchorTag& tag) {
  JsonObject a(json, where, name);
  tag.id = a.integer("id", 0, -2000000000, 2000000000);
  tag.releaseFrame = a.integer("release_frame", -1, -1, 2000000000);
  tag.name = a.string("name", "");
  AnchorConstraint c;
  const nlohmann::json& vertices = a.raw("vertices");
  if (!vertices.is_array()) a.fail("vertices", "must be a list of vertex indices");
  for (const nlohmann::json& v : vertices) {
    if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() >= nv)
      a.fail("vertices", "holds " + v.dump() + ", not a vertex of the mesh (it has " +
                             std::to_string(nv) + ")");
    c.vertices.push_back(v.get<int>());
  }
  const auto origin = a.array("origin");
  for (size_t k = 0; k < origin.size(); ++k) {
    const nlohmann::json wrapped = {{"p", origin[k]}};
    JsonObject w(wrapped, a.childPath("origin") + "[" + std::to_string(k) + "]", name);
    c.origin.push_back(readVec(w, "p"));
  }
  if (!c.origin.empty() && c.origin.size() != c.vertices.size())
    a.fail("origin", "must hold one point per vertex");
  const auto weights = a.array("spring_weights");
  for (size_t k = 0; k < weights.size(); ++k) {
    const double w = weights[k].is_number() ? weights[k].get<double>() : -1.0;
    if (!(w >= 0.0 && w <= 1.0))
      a.fail("spring_weights", "holds " + weights[k].dump() + ", not a weight in [0, 1]");
    c.springWeights.push_back(w);
  }
  if (!c.springWeights.empty() && c.springWeights.size() != c.vertices.size())
    a.fail("spring_weights", "must hold one weight per vertex");
  const auto path = a.array("path");
  for (size_t k = 0; k < path.size(); ++k) {
    JsonObject key(path[k], a.childPath("path") + "[" + std::to_string(k) + "]", name);
    AnchorKey ak;
    ak.time = key.number("time", 0.0, -1e12, 1e12);
    ak.offset = readVec(key, "offset");
    key.rejectUnknownKeys();
    c.path.push_back(ak);
  }
  a.rejectUnknownKeys();
  return c;
}

struct ProjectCounts {
  int vertices = 0, tets = 0, edges = 0, version = 1;
  bool plastic = false;
  int solverCarry = 0;  // doubles (version 3)
};

// The binary arrays after the header: rest mesh, positions, velocities, damage (and blade
// crossings from version 2), plastic state; each checked before use.
void readProjectArrays(BinaryReader& in, const ProjectCounts& n, const std::string& name,
                       Project& p) {
  SimulationSnapshot& s = p.state;
  const int nv = n.vertices, nt = n.tets, ne = n.edges;
  const int version = n.version;
  const bool plastic = n.plastic;
  std::vector<double> rest, x, v;
  std::vector<int> tets;
  in.read(rest, 3 * static_cast<std::size_t>(nv), "rest vertices");
  in.read(tets, 4 * static_cast<std::size_t>(nt), "tets");
  in.read(x, 3 * static_cast<std::size_t>(nv), "positions");
  in.read(v, 3 * static_cast<std::size_t>(nv), "velocities");
  in.read(s.damaged, static_cast<std::size_t>(ne), "damage");
  if (version >= 2) {
    in.read(s.crossing, static_cast<std::size_t>(ne), "blade crossings");
  } else {
    s.crossing.assign(static_cast<std::size_t>(ne), kNoCrossing);
  }
  checkFinite(rest, name, "rest vertices");
  checkFinite(x, name, "positions");
  checkFinite(v, name, "velocities");
  for (size_t i = 0; i < tets.size(); ++i)
    if (tets[i] < 0 || tets[i] >= nv)
      throw InputError(name + ": tet " + std::to_string(i / 4) + " names vertex " +
                       std::to_string(tets[i]) + " (the mesh has " + std::to_string(nv) + ")");
  for (size_t e = 0; e < s.damaged.size(); ++e)
    if (s.damaged[e] > 1)
      throw InputError(name + ": damage of edge " + std::to_string(e) + " is " +
                       std::to_string(s.damaged[e]) + " (must be 0 or 1)");
  for (size_t e = 0; e < s.crossing.size(); ++e)
    if (s.crossing[e] != kNoCrossing && !(s.damaged[e] && hasCrossing(s.crossing[e])))
      throw InputError(name + ": blade crossing of edge " + std::to_string(e) + " is " +
                       std::to_string(s.crossing[e]) +
                       (s.damaged[e] ? " (must be -1 or a fraction in [0, 1])"
                                     : " on an undamaged edge (must be -1)"));
  if (plastic) {
    std::vector<double> inverse;
    in.read(inverse, 9 * static_cast<std::size_t>(nt), "plastic state");
    in.read(s.plasticStrain, static_cast<std::size_t>(nt), "plastic strain");
    checkFinite(inverse, name, "plastic state");
    checkFinite(s.plasticStrain, name, "plastic strain");
    for (size_t t = 0; t < s.plasticStrain.size(); ++t)
      if (s.plasticStrain[t] < 0.0)
        throw InputError(name + ": plastic strain: value " + std::to_string(t) + " is negative");
    for (int t = 0; t < nt; ++t)
      s.plasticInverse.push_back(Eigen::Map<const Eigen::Matrix3d>(&inverse[9 * t]));
  }
  in.read(s.solverCarry, static_cast<std::size_t>(n.solverCarry), "solver carry");
  checkFinite(s.solverCarry, name, "solver carry");
  if (!in.atEnd())
    throw InputError(name + ": unexpected data after byte " + std::to_string(in.offset()));
  p.mesh.vertices = unflat(rest);
  p.mesh.tets.resize(nt);
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 4; ++k) p.mesh.tets[t][k] = tets[4 * t + k];
  s.x = unflat(x);
  s.v = unflat(v);
}

}  // namespace

Project readProject(const fs::path& file) {
  const std::string name = file.string();
  std::string data = readWholeFile(file);
  std::size_t line1 = 0;
  const int version = readProjectVersion(data, name, line1);
  const std::size_t line2 = data.find('\n', line1 + 1);
  std::size_t headerBytes = 0;
  try {
    if (line2 == std::string::npos) throw std::invalid_argument("missing");
    headerBytes = std::stoull(data.substr(line1 + 1, line2 - line1 - 1));
  } catch (const std::exception&) {
    throw InputError(name, 2, "the header length is missing or not a number");
  }
  if (data.size() - (line2 + 1) < headerBytes)
    throw InputError(name, 3,
                     "truncated: the header needs " + std::to_string(headerBytes) +
                         " bytes, the file has " + std::to_string(data.size() - line2 - 1) +
                         " after line 2");
  const nlohmann::json h = parseJsonText(data.substr(line2 + 1, headerBytes), name, 3);
  JsonObject o(h, "$", name);
  Project p;
  if (!o.has("scene")) o.fail("scene", "is required");
  const fs::path sceneFile = o.string("scene_file", "scene.json");
  try {
    p.scene = parseScene(o.raw("scene"), sceneFile);
  } catch (const InputError& e) {
    // The scene is the project's copy: name the project, then what the scene reader said.
    throw InputError(name + ": $.scene (saved from " + sceneFile.string() + "): " + e.what());
  }
  SimulationSnapshot& s = p.state;
  s.frame = o.integer("frame", 0, 0, 2000000000);
  s.time = o.number("time", 0.0, 0.0, 1e12);
  // Rigid pendulums' states (files written before they existed: the colliders' initial states).
  const auto colliders = o.array("colliders");
  if (o.has("colliders") && colliders.size() != p.scene.colliders.size())
    o.fail("colliders", "holds " + std::to_string(colliders.size()) + " states; the scene has " +
                            std::to_string(p.scene.colliders.size()) + " colliders");
  for (size_t i = 0; i < p.scene.colliders.size(); ++i) {
    ColliderState c = initialColliderState(p.scene.colliders[i]);
    if (i < colliders.size()) {
      JsonObject j(colliders[i], o.childPath("colliders") + "[" + std::to_string(i) + "]", name);
      c.angle = j.number("angle", 0.0, -1e9, 1e9);
      c.angularVelocity = j.number("angular_velocity", c.angularVelocity, -1e9, 1e9);
      j.rejectUnknownKeys();
    }
    s.colliders.push_back(c);
  }
  const int nv = o.integer("vertices", 0, 4, 2000000000);
  const int nt = o.integer("tets", 0, 1, 2000000000);
  const int ne = o.integer("edges", 0, 6, 2000000000);
  const bool plastic = o.boolean("plastic", false);
  s.toolDamage = o.integer("tool_damage", 0, 0, 2000000000);
  const int solverCarry = o.integer("solver_carry", 0, 0, 200000000);
  s.nextAnchorId = o.integer("next_anchor_id", 0, 0, 2000000000);
  s.letGo = o.boolean("let_go", false);
  const auto anchors = o.array("anchors");
  for (size_t i = 0; i < anchors.size(); ++i) {
    AnchorTag tag;
    s.anchors.push_back(
        readAnchor(anchors[i], "$.anchors[" + std::to_string(i) + "]", nv, name, tag));
    s.anchorTags.push_back(std::move(tag));
  }
  const auto events = o.array("recording");
  for (size_t i = 0; i < events.size(); ++i)
    p.recording.push_back(
        parseToolEvent(events[i], "$.recording[" + std::to_string(i) + "]", name));
  if (o.has("camera")) {
    JsonObject c = o.object("camera");
    p.camera = readCameraPose(c);
    c.rejectUnknownKeys();
  }
  o.rejectUnknownKeys();

  BinaryReader in(std::move(data), line2 + 1 + headerBytes, name);
  readProjectArrays(in, ProjectCounts{nv, nt, ne, version, plastic, solverCarry}, name, p);
  return p;
}

}  // namespace galsculpt
