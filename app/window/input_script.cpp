#include "app/window/input_script.h"

#include "engine/scene/json_reader.h"
#include "solver/io/input_error.h"

namespace galsculpt {

namespace {

MouseButton buttonNamed(JsonObject& o, const std::string& key) {
  const std::string name = o.string(key, "left", {"left", "right", "middle"});
  return name == "left"    ? MouseButton::Left
         : name == "right" ? MouseButton::Right
                           : MouseButton::Middle;
}

int keyNamed(JsonObject& o) {
  const std::string name = o.string("key", "");
  if (name.size() == 1) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
    if ((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '[' || c == ']' || c == '.')
      return c;
  }
  if (name == "space") return ' ';
  if (name == "escape") return kKeyEscape;
  o.fail("key",
         "must be a letter, a digit, '[', ']', '.', 'space' or 'escape', got '" + name + "'");
}

}  // namespace

InputScript loadInputScript(const std::filesystem::path& file) {
  const nlohmann::json root = parseJsonFile(file);
  JsonObject top(root, "$", file.string());
  InputScript script;
  std::vector<InputStep>& steps = script.steps;
  script.realtime = top.boolean("realtime", false);
  const auto list = top.array("steps");
  if (!top.has("steps")) top.fail("steps", "is required (a list of input steps)");
  top.rejectUnknownKeys();
  for (size_t i = 0; i < list.size(); ++i) {
    JsonObject o(list[i], "$.steps[" + std::to_string(i) + "]", file.string());
    InputStep s;
    s.jsonPath = o.path();
    s.shift = o.boolean("shift", false);
    s.ctrl = o.boolean("ctrl", false);
    if (o.has("wait")) {
      s.kind = InputStep::Kind::Wait;
      s.frames = o.integer("wait", 1, 0, 1000000);
    } else if (o.has("wait_frames")) {
      // Real time: until this many more simulation frames are on the screen (the file is
      // loaded and playing); in a synchronous script the same as "wait".
      s.kind = InputStep::Kind::WaitFrames;
      s.frames = o.integer("wait_frames", 1, 0, 1000000);
    } else if (o.has("move")) {
      s.kind = InputStep::Kind::Move;
      const nlohmann::json& m = o.raw("move");
      // One point [x, y] or a list of points, all delivered within one frame.
      const bool single = m.is_array() && m.size() == 2 && m[0].is_number();
      const nlohmann::json points = single ? nlohmann::json::array({m}) : m;
      if (!points.is_array() || points.empty()) o.fail("move", "must be [x, y] or [[x, y], ...]");
      for (const nlohmann::json& p : points) {
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
          o.fail("move", "must be [x, y] or [[x, y], ...] (fractions of the window)");
        s.points.emplace_back(p[0].get<double>(), p[1].get<double>());
      }
    } else if (o.has("press")) {
      s.kind = InputStep::Kind::Press;
      s.button = buttonNamed(o, "press");
    } else if (o.has("release")) {
      s.kind = InputStep::Kind::Release;
      s.button = buttonNamed(o, "release");
    } else if (o.has("scroll")) {
      s.kind = InputStep::Kind::Scroll;
      s.scroll = o.number("scroll", 0.0, -1000.0, 1000.0);
    } else if (o.has("key")) {
      s.kind = InputStep::Kind::Key;
      s.key = keyNamed(o);
    } else if (o.has("command")) {
      s.kind = InputStep::Kind::Command;
      s.command = *scriptCommandNamed(o.string("command", "", scriptCommandNames()));
      s.argument = o.string("argument", "");
    } else {
      o.fail("", "needs one of wait, wait_frames, move, press, release, scroll, key or command");
    }
    o.rejectUnknownKeys();
    steps.push_back(std::move(s));
  }
  return script;
}

InputScriptRunner::Turn InputScriptRunner::next(int viewsShown, bool inputNotYetShown) {
  using Kind = Turn::Kind;
  if (wait_ > 0) {
    --wait_;
    return {Kind::Hold};
  }
  if (waitViews_ >= 0) {
    if (viewsShown < waitViews_) return {Kind::Hold};
    waitViews_ = -1;
  }
  if (next_ >= script_.steps.size()) return {Kind::Done};
  const InputStep& s = script_.steps[next_];
  if (s.kind == InputStep::Kind::Command && s.command == AppCommand::Screenshot && inputNotYetShown)
    return {Kind::Hold};
  ++next_;
  if (s.kind == InputStep::Kind::Wait) {
    wait_ = s.frames;
    return {Kind::Hold};
  }
  if (s.kind == InputStep::Kind::WaitFrames) {
    if (script_.realtime)
      waitViews_ = viewsShown + s.frames;
    else
      wait_ = s.frames;
    return {Kind::Hold};
  }
  return {Kind::Act, &s};
}

}  // namespace galsculpt
