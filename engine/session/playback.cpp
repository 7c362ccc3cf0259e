#include "engine/session/playback.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "engine/session/tool_reach.h"
#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

Vec3 readPoint(JsonObject& o, const std::string& key, const nlohmann::json& value) {
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
      !value[2].is_number())
    o.fail(key, "must be a point [x, y, z]");
  const Vec3 p(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
  if (!(p.cwiseAbs().maxCoeff() <= kMaxCoordinate))  // NaN fails too
    o.fail(key, "points must be within +-1e+06 m in each coordinate");
  return p;
}

// A blade: [[x, y, z], [x, y, z]].
std::pair<Vec3, Vec3> readBlade(JsonObject& o, const std::string& key) {
  if (!o.has(key)) o.fail(key, "is required for a knife (the blade's two ends)");
  const nlohmann::json& v = o.raw(key);
  if (!v.is_array() || v.size() != 2) o.fail(key, "must be two points [[x, y, z], [x, y, z]]");
  return {readPoint(o, key, v[0]), readPoint(o, key, v[1])};
}

Symmetry readSymmetry(JsonObject& o) {
  Symmetry s;
  if (!o.has("symmetry")) return s;
  JsonObject m = o.object("symmetry");
  const std::string axis = m.string("axis", "", {"x", "y", "z"});
  if (axis.empty()) m.fail("axis", "is required (x, y or z)");
  s.axis = axis[0] - 'x';
  s.offset = m.number("offset", 0.0, -1e9, 1e9);
  m.rejectUnknownKeys();
  return s;
}

Vec3 readUnit(JsonObject& o, const std::string& key) {
  const Vec3 n = o.vec3(key, Vec3::UnitY());
  if (!(n.norm() > 1e-12)) o.fail(key, "must be a non-zero direction");
  // A recorded unit normal is kept bit for bit (normalizing it again can change its last bit,
  // and a replay must be exact); a hand-written one is normalized.
  return std::abs(n.norm() - 1.0) < 1e-12 ? n : Vec3(n.normalized());
}

void readStroke(JsonObject& o, ToolEvent& e) {
  if (!o.has("center")) o.fail("center", "is required for a brush stroke");
  e.stroke.center = o.vec3("center", Vec3::Zero(), kMaxCoordinate);
  e.stroke.normal = readUnit(o, "normal");
  e.stroke.radius = o.requiredNumber("radius", 1e-9, 1e9);
  e.stroke.strength = o.number("strength", 0.0, 0.0, 1e9);
  e.stroke.seed = o.integer("seed", -1, 0, 2000000000);
  e.end = o.integer("end", e.frame, e.frame, 100000000);
  const auto moves = o.array("moves");
  int last = e.frame;
  for (size_t i = 0; i < moves.size(); ++i) {
    JsonObject m(moves[i], o.childPath("moves") + "[" + std::to_string(i) + "]", o.file());
    StrokeKey k;
    k.frame = m.integer("frame", 0, 0, 100000000);
    if (!m.has("frame")) m.fail("frame", "is required");
    if (k.frame < last || k.frame > e.end)
      m.fail("frame", "must not go back in time and must lie between the stroke's frame (" +
                          std::to_string(e.frame) + ") and its end (" + std::to_string(e.end) +
                          ")");
    last = k.frame;
    if (!m.has("center")) m.fail("center", "is required");
    k.center = m.vec3("center", Vec3::Zero(), kMaxCoordinate);
    k.normal = readUnit(m, "normal");
    m.rejectUnknownKeys();
    e.moves.push_back(k);
  }
}

ToolEvent readEvent(JsonObject o) {
  ToolEvent e;
  e.path = o.path();
  // The tools of the table (tool_table.h) that a script can hold, and the script's own events:
  // a fixed drag (brush), an anchor by shape, the camera.
  static const std::vector<std::string> kEventNames = [] {
    std::vector<std::string> names;
    for (const ToolRow& row : toolTable())
      if (row.kind != ToolKind::Navigate) names.push_back(row.name);
    for (const char* scriptOnly : {"brush", "anchor", "camera"}) names.push_back(scriptOnly);
    return names;
  }();
  const std::string tool = o.string("tool", "", kEventNames);
  if (tool.empty()) {
    std::string names;
    for (size_t i = 0; i < kEventNames.size(); ++i)
      names += (i == 0 ? "" : i + 1 == kEventNames.size() ? " or " : ", ") + kEventNames[i];
    o.fail("tool", "is required (" + names + ")");
  }
  e.frame = o.integer("frame", 0, 0, 100000000);
  e.duration = o.integer("duration", 1, 1, 100000000);
  if (tool == "knife") {
    e.kind = ToolEvent::Kind::Knife;
    e.stroke.kind = Tool::Knife;
    std::tie(e.from0, e.from1) = readBlade(o, "from");
    std::tie(e.to0, e.to1) = readBlade(o, "to");
    e.stroke.symmetry = readSymmetry(o);
  } else if (tool == "brush") {
    e.kind = ToolEvent::Kind::Drag;
    if (!o.has("center")) o.fail("center", "is required for a brush");
    e.stroke.center = o.vec3("center", Vec3::Zero(), kMaxCoordinate);
    e.stroke.radius = o.requiredNumber("radius", 1e-9, 1e9);
    e.offset = o.vec3("offset", Vec3::Zero(), kMaxCoordinate);
    e.hold = o.boolean("hold", false);
  } else if (tool == "anchor") {
    e.kind = ToolEvent::Kind::Anchor;
    e.add = o.string("action", "add", {"add", "remove"}) == "add";
    e.name = o.string("name", "");
    if (e.add) {
      if (!o.has("anchor"))
        o.fail("anchor", "is required to add an anchor (box, sphere or vertices)");
      e.shape = readAnchorDesc(o.object("anchor"));
    } else {
      e.sceneAnchor = o.integer("scene_anchor", -1, 0, 1000000);
      if (e.name.empty() == (e.sceneAnchor < 0))
        o.fail("name", "give either the name of an added anchor or scene_anchor (an index)");
    }
  } else if (tool == "camera") {
    e.kind = ToolEvent::Kind::Camera;
    e.camera = readCameraPose(o);
  } else if (toolRow(*toolNamed(tool)).kind == ToolKind::Paint) {  // (a tool: o.string checked)
    e.kind = ToolEvent::Kind::Paint;
    e.stroke.kind = *toolNamed(tool);
    if (!o.has("center")) o.fail("center", "is required for anchor paint");
    e.stroke.center = o.vec3("center", Vec3::Zero(), kMaxCoordinate);
    e.stroke.radius = o.requiredNumber("radius", 1e-9, 1e9);
    e.stroke.seed = o.integer("seed", -1, 0, 2000000000);
    e.stroke.symmetry = readSymmetry(o);
  } else {
    e.kind = ToolEvent::Kind::Stroke;
    e.stroke.kind = *toolNamed(tool);  // (a brush: the other names are read above)
    readStroke(o, e);
    e.stroke.symmetry = readSymmetry(o);
  }
  o.rejectUnknownKeys();
  return e;
}

}  // namespace

PlaybackScript loadPlaybackScript(const fs::path& file) {
  refuseMeshAsJson(file);
  return parsePlaybackScript(parseJsonFile(file), file);
}

PlaybackScript parsePlaybackScript(const nlohmann::json& root, const fs::path& file) {
  JsonObject o(root, "$", file.string());
  PlaybackScript s;
  s.file = fs::absolute(file);
  const std::string scene = o.string("scene", "");
  if (scene.empty()) o.fail("scene", "is required (a scene file, relative to the script)");
  const fs::path scenePath = s.file.parent_path() / scene;
  if (!fs::exists(scenePath)) {
    std::string message = "does not exist: ";
    message += scenePath.string();
    o.fail("scene", message);
  }
  s.scene = loadScene(scenePath);
  s.frames = o.integer("frames", 0, 1, 100000000);
  if (!o.has("frames")) o.fail("frames", "is required");
  const auto events = o.array("events");
  for (size_t i = 0; i < events.size(); ++i) {
    s.events.push_back(
        parseToolEvent(events[i], "$.events[" + std::to_string(i) + "]", file.string()));
  }
  for (const ToolEvent& e : s.events) {
    // An event after the last frame would never happen (one at the last frame does: a cut made
    // just before saving is applied after it).
    if (e.frame > s.frames)
      throw InputError(file.string(), 0,
                       e.path + ".frame: " + std::to_string(e.frame) +
                           " is after the script's last frame (" + std::to_string(s.frames) +
                           "): the event would never happen");
  }
  std::stable_sort(s.events.begin(), s.events.end(),
                   [](const ToolEvent& a, const ToolEvent& b) { return a.frame < b.frame; });
  // Names must be added before they are removed, and scene anchors must exist.
  std::map<std::string, int> added;
  for (const ToolEvent& e : s.events) {
    if (e.kind != ToolEvent::Kind::Anchor) continue;
    if (e.add && !e.name.empty()) ++added[e.name];
    if (!e.add && !e.name.empty() && added[e.name]-- <= 0)
      throw InputError(file.string(), 0,
                       e.path + ".name: no anchor '" + e.name + "' is added before frame " +
                           std::to_string(e.frame));
    if (!e.add && e.sceneAnchor >= static_cast<int>(s.scene.anchors.size()))
      throw InputError(file.string(), 0,
                       e.path + ".scene_anchor: the scene has " +
                           std::to_string(s.scene.anchors.size()) + " anchor(s)");
  }
  o.rejectUnknownKeys();
  return s;
}

CameraPose readCameraPose(JsonObject& o) {
  CameraPose pose;
  pose.target = o.vec3("target", Vec3::Zero(), kMaxCoordinate);
  pose.distance = o.requiredNumber("distance", 1e-9, 1e12);
  pose.yaw = o.number("yaw", 0.0, -1e6, 1e6);
  pose.pitch = o.number("pitch", 0.0, -1.6, 1.6);
  return pose;
}

nlohmann::json cameraPoseJson(const CameraPose& pose) {
  return {{"target", vec3Json(pose.target)},
          {"distance", pose.distance},
          {"yaw", pose.yaw},
          {"pitch", pose.pitch}};
}

ToolEvent parseToolEvent(const nlohmann::json& value, const std::string& path,
                         const std::string& file) {
  ToolEvent e = readEvent(JsonObject(value, path, file));
  e.source = value;
  return e;
}

nlohmann::json toolEventJson(const ToolEvent& e) {
  nlohmann::json j;
  j["frame"] = e.frame;
  auto symmetry = [&] {
    if (e.stroke.symmetry.enabled())
      j["symmetry"] = {{"axis", std::string(1, static_cast<char>('x' + e.stroke.symmetry.axis))},
                       {"offset", e.stroke.symmetry.offset}};
  };
  switch (e.kind) {
    case ToolEvent::Kind::Knife:
      j["tool"] = "knife";
      j["duration"] = e.duration;
      j["from"] = {vec3Json(e.from0), vec3Json(e.from1)};
      j["to"] = {vec3Json(e.to0), vec3Json(e.to1)};
      symmetry();
      break;
    case ToolEvent::Kind::Drag:
      j["tool"] = "brush";
      j["duration"] = e.duration;
      j["center"] = vec3Json(e.stroke.center);
      j["radius"] = e.stroke.radius;
      j["offset"] = vec3Json(e.offset);
      if (e.hold) j["hold"] = true;
      break;
    case ToolEvent::Kind::Anchor: {
      // Written by hand in a script the app replayed or given to SculptSession::apply: kept as
      // written, at the frame where it acted.
      if (e.source.is_null()) throw std::invalid_argument("an anchor event with no source");
      nlohmann::json source = e.source;
      source["frame"] = e.frame;
      return source;
    }
    case ToolEvent::Kind::Stroke: {
      j["tool"] = toolRow(e.stroke.kind).name;
      j["center"] = vec3Json(e.stroke.center);
      j["normal"] = vec3Json(e.stroke.normal);
      j["radius"] = e.stroke.radius;
      j["strength"] = e.stroke.strength;
      if (e.stroke.seed >= 0) j["seed"] = e.stroke.seed;
      j["end"] = e.end;
      nlohmann::json moves = nlohmann::json::array();
      for (const StrokeKey& k : e.moves)
        moves.push_back(
            {{"frame", k.frame}, {"center", vec3Json(k.center)}, {"normal", vec3Json(k.normal)}});
      j["moves"] = moves;
      symmetry();
      break;
    }
    case ToolEvent::Kind::Paint:
      j["tool"] = toolRow(e.stroke.kind).name;
      j["center"] = vec3Json(e.stroke.center);
      j["radius"] = e.stroke.radius;
      if (e.stroke.seed >= 0) j["seed"] = e.stroke.seed;
      symmetry();
      break;
    case ToolEvent::Kind::Camera:
      j.update(cameraPoseJson(e.camera));
      j["tool"] = "camera";
      break;
  }
  return j;
}

void writePlaybackScript(const fs::path& file, const fs::path& scene, int frames,
                         const std::vector<ToolEvent>& events) {
  nlohmann::json root;
  const fs::path folder = fs::absolute(file).parent_path();
  root["scene"] = fs::absolute(scene).lexically_relative(folder).generic_string();
  root["frames"] = std::max(frames, 1);
  nlohmann::json list = nlohmann::json::array();
  for (const ToolEvent& e : events) list.push_back(toolEventJson(e));
  root["events"] = list;
  const std::string text = root.dump(1) + "\n";
  writeFileAtomically(file, [&](std::ostream& out) { out << text; });
}

void checkToolEvent(const ToolEvent& e, const Simulation& sim, const std::string& file) {
  if (e.kind == ToolEvent::Kind::Anchor && e.add)
    sim.selectVertices(e.shape, file, e.path + ".anchor");
  if (e.stroke.seed >= sim.model().numVertices())
    throw InputError(file, 0,
                     e.path + ".seed: " + std::to_string(e.stroke.seed) +
                         " is not a vertex of the mesh (it has " +
                         std::to_string(sim.model().numVertices()) + ")");
}

void checkScriptAnchors(const PlaybackScript& script, const Simulation& sim) {
  for (const ToolEvent& e : script.events) checkToolEvent(e, sim, script.file.string());
}

Playback::Playback(const PlaybackScript& script, Simulation& sim)
    : script_(script), sim_(sim), tools_(sim, script.file.string()) {
  checkScriptAnchors(script_, sim_);
}

void ToolApplier::prepareFrame(const std::vector<ToolEvent>& events, int frame) {
  sim_.anchors().releaseDue(frame);
  for (const ToolEvent& e : events) apply(e, frame);
  sculptor_.beforeFrame();
}

void ToolApplier::applyTrailing(const std::vector<ToolEvent>& events, int lastFrame) {
  for (const ToolEvent& e : events) {
    if (e.kind == ToolEvent::Kind::Knife && e.frame == lastFrame) apply(e, lastFrame);
  }
}

int ToolApplier::apply(const ToolEvent& e, int frame) {
  const int step = frame - e.frame;
  const double dt = sim_.settings().dt;
  switch (e.kind) {
    case ToolEvent::Kind::Knife: {
      if (step < 0 || step >= e.duration) break;
      // The blade moves linearly over the stroke; each frame cuts everything across the slit
      // it has swept so far, at the current positions: material that moved across the slit
      // behind the blade (a cut body relaxes as the blade goes on) is cut too, not skipped.
      const double u1 = static_cast<double>(step + 1) / e.duration;
      auto at = [](const Vec3& a, const Vec3& b, double u) { return Vec3((1.0 - u) * a + u * b); };
      const std::vector<BladeTriangle> blade =
          sweptBladeSurface(e.from0, e.from1, at(e.from0, e.to0, u1), at(e.from1, e.to1, u1));
      const int cut = sculptor_.cut(blade, e.stroke.symmetry);
      const std::string key = e.path + "@" + std::to_string(e.frame);
      knifeCuts_[key] += cut;
      if (step == e.duration - 1) {
        if (knifeCuts_[key] == 0) {
          std::ostringstream what;
          what << "crossed no edge: its blade passed " << std::setprecision(3)
               << distanceToBlade(blade, sim_.state().x) << " m from the nearest vertex";
          reportIdle(e, frame, what.str());
        }
        knifeCuts_.erase(key);
      }
      return cut;
    }
    case ToolEvent::Kind::Drag: {
      if (step != 0) break;
      const std::vector<int> grabbed = sim_.verticesNear(e.stroke.center, e.stroke.radius);
      if (grabbed.empty()) {  // a brush stroke in empty space moves nothing, and says so
        reportIdle(e, frame, "reached no vertex: " + nearestText(e.stroke.center, e.stroke.radius));
        break;
      }
      sim_.anchors().add(grabbed, {{0.0, Vec3::Zero()}, {e.duration * dt, e.offset}},
                         e.hold ? -1 : e.frame + e.duration);
      break;
    }
    case ToolEvent::Kind::Anchor: {
      if (step != 0) break;
      if (e.add) {
        sim_.anchors().add(sim_.selectVertices(e.shape, file_, e.path + ".anchor"), {}, -1, e.name);
      } else if (!e.name.empty()) {
        const std::optional<int> id = sim_.anchors().named(e.name);
        if (!id)
          throw InputError(file_, 0,
                           e.path + ".name: no anchor named \"" + e.name + "\" holds now");
        sim_.anchors().remove(*id);
      } else {
        sim_.anchors().remove(-e.sceneAnchor - 1);
      }
      break;
    }
    case ToolEvent::Kind::Stroke: {
      if (frame < e.frame || frame > e.end) break;
      if (step == 0) {
        sculptor_.beginBrush(e.stroke);
      }
      for (const StrokeKey& k : e.moves)
        if (k.frame == frame) sculptor_.moveBrush(k.center, k.normal);
      if (frame == e.end) {
        // A stroke that never acted (begun and ended in one frame) has reached nothing to say.
        if (sculptor_.strokeReach() == 0 && (e.end > e.frame || e.stroke.kind == Tool::Grab))
          reportIdle(e, frame,
                     "reached no vertex: " + nearestText(e.stroke.center, e.stroke.radius));
        sculptor_.endBrush();
      }
      break;
    }
    case ToolEvent::Kind::Paint:
      if (step == 0 && sculptor_.paintAnchors(e.stroke.center, e.stroke.radius, e.stroke.seed,
                                              e.erase(), e.stroke.symmetry) == 0) {
        reportIdle(e, frame,
                   std::string(e.erase() ? "freed" : "anchored") +
                       " no vertex: " + nearestText(e.stroke.center, e.stroke.radius));
      }
      break;
    case ToolEvent::Kind::Camera:
      if (step == 0) camera_ = e.camera;
      break;
  }
  return 0;
}

std::string ToolApplier::nearestText(const Vec3& center, double radius) const {
  const int v = sim_.nearestVertex(center);
  std::ostringstream s;
  s << std::setprecision(3) << "the nearest is " << (sim_.state().x[v] - center).norm()
    << " m from its centre (radius " << radius << " m)";
  return s.str();
}

void ToolApplier::reportIdle(const ToolEvent& e, int frame, const std::string& what) {
  idle_.push_back("frame " + std::to_string(frame) + ": " + toolEventJson(e).value("tool", "tool") +
                  (e.path.empty() ? "" : " (" + e.path + ")") + " " + what);
}

FrameMetrics Playback::advance() {
  const int frame = sim_.frame();  // the frame about to be computed is frame + 1
  const int idleBefore = tools_.idleCount();
  tools_.prepareFrame(script_.events, frame);
  FrameMetrics m = sim_.advance();
  // The metrics are the frame's; trailing cuts show in the state (and the final surface).
  if (finished()) tools_.applyTrailing(script_.events, sim_.frame());
  m.idleTools = tools_.idleCount() - idleBefore;
  return m;
}

}  // namespace galsculpt
