#include "playback.h"

#include <algorithm>

#include "solver/input_error.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

Vec3 readPoint(JsonObject& o, const std::string& key, const nlohmann::json& value) {
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
      !value[2].is_number())
    o.fail(key, "must be a point [x, y, z]");
  return Vec3(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
}

// A blade: [[x, y, z], [x, y, z]].
std::pair<Vec3, Vec3> readBlade(JsonObject& o, const std::string& key) {
  if (!o.has(key)) o.fail(key, "is required for a knife (the blade's two ends)");
  const nlohmann::json& v = o.raw(key);
  if (!v.is_array() || v.size() != 2) o.fail(key, "must be two points [[x, y, z], [x, y, z]]");
  return {readPoint(o, key, v[0]), readPoint(o, key, v[1])};
}

ToolEvent readEvent(JsonObject o) {
  ToolEvent e;
  e.path = o.path();
  const std::string tool = o.string("tool", "", {"knife", "brush", "anchor"});
  if (tool.empty()) o.fail("tool", "is required (knife, brush or anchor)");
  e.frame = o.integer("frame", 0, 0, 100000000);
  e.duration = o.integer("duration", 1, 1, 100000000);
  if (tool == "knife") {
    e.tool = ToolEvent::Tool::Knife;
    std::tie(e.from0, e.from1) = readBlade(o, "from");
    std::tie(e.to0, e.to1) = readBlade(o, "to");
  } else if (tool == "brush") {
    e.tool = ToolEvent::Tool::Brush;
    if (!o.has("center")) o.fail("center", "is required for a brush");
    e.center = o.vec3("center", Vec3::Zero());
    e.radius = o.requiredNumber("radius", 1e-9, 1e9);
    e.offset = o.vec3("offset", Vec3::Zero());
    e.hold = o.boolean("hold", false);
  } else {
    e.tool = ToolEvent::Tool::Anchor;
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
  }
  o.rejectUnknownKeys();
  return e;
}

}  // namespace

PlaybackScript loadPlaybackScript(const fs::path& file) {
  const nlohmann::json root = parseJsonFile(file);
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
        readEvent(JsonObject(events[i], "$.events[" + std::to_string(i) + "]", file.string())));
  }
  std::stable_sort(s.events.begin(), s.events.end(),
                   [](const ToolEvent& a, const ToolEvent& b) { return a.frame < b.frame; });
  // Names must be added before they are removed, and scene anchors must exist.
  std::map<std::string, int> added;
  for (const ToolEvent& e : s.events) {
    if (e.tool != ToolEvent::Tool::Anchor) continue;
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

Playback::Playback(const PlaybackScript& script, Simulation& sim) : script_(script), sim_(sim) {
  for (const ToolEvent& e : script_.events) {
    if (e.tool == ToolEvent::Tool::Anchor && e.add)
      sim_.selectVertices(e.shape, script_.file.string(), e.path + ".anchor");
  }
}

void Playback::apply(const ToolEvent& e, int step) {
  const double dt = sim_.settings().dt;
  switch (e.tool) {
    case ToolEvent::Tool::Knife: {
      // The blade moves linearly over the stroke; each frame cuts what it swept.
      const double u0 = static_cast<double>(step) / e.duration;
      const double u1 = static_cast<double>(step + 1) / e.duration;
      auto at = [](const Vec3& a, const Vec3& b, double u) { return Vec3((1.0 - u) * a + u * b); };
      sim_.cut(sweptBladeSurface(at(e.from0, e.to0, u0), at(e.from1, e.to1, u0),
                                 at(e.from0, e.to0, u1), at(e.from1, e.to1, u1)));
      break;
    }
    case ToolEvent::Tool::Brush: {
      if (step != 0) break;
      const std::vector<int> grabbed = sim_.verticesNear(e.center, e.radius);
      if (grabbed.empty()) break;  // a brush stroke in empty space moves nothing
      const int id = sim_.addAnchor(grabbed, {{0.0, Vec3::Zero()}, {e.duration * dt, e.offset}});
      if (!e.hold) releases_.push_back({e.frame + e.duration, id});
      break;
    }
    case ToolEvent::Tool::Anchor: {
      if (step != 0) break;
      if (e.add) {
        const int id =
            sim_.addAnchor(sim_.selectVertices(e.shape, script_.file.string(), e.path + ".anchor"));
        if (!e.name.empty()) namedAnchors_[e.name] = id;
      } else if (!e.name.empty()) {
        sim_.removeAnchor(namedAnchors_.at(e.name));
        namedAnchors_.erase(e.name);
      } else {
        sim_.removeAnchor(-e.sceneAnchor - 1);
      }
      break;
    }
  }
}

FrameMetrics Playback::advance() {
  const int frame = sim_.frame();  // the frame about to be computed is frame + 1
  for (auto it = releases_.begin(); it != releases_.end();) {
    if (it->first <= frame) {
      sim_.removeAnchor(it->second);
      it = releases_.erase(it);
    } else {
      ++it;
    }
  }
  for (const ToolEvent& e : script_.events) {
    const int step = frame - e.frame;
    if (step >= 0 && step < (e.tool == ToolEvent::Tool::Knife ? e.duration : 1)) apply(e, step);
  }
  return sim_.advance();
}

}  // namespace galsculpt
