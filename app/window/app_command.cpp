#include "app/window/app_command.h"

#include <array>
#include <utility>

#include "app/window/tool_controller.h"

namespace galsculpt {

namespace {

constexpr std::array<std::pair<AppCommand, const char*>, 21> kScriptNames = {{
    {AppCommand::Open, "open"},
    {AppCommand::SaveProject, "save_project"},
    {AppCommand::SaveRecording, "save_recording"},
    {AppCommand::Export, "export"},
    {AppCommand::ExportTets, "export_tets"},
    {AppCommand::Undo, "undo"},
    {AppCommand::Redo, "redo"},
    {AppCommand::Reset, "reset"},
    {AppCommand::Play, "play"},
    {AppCommand::Pause, "pause"},
    {AppCommand::Step, "step"},
    {AppCommand::Tool, "tool"},
    {AppCommand::Radius, "radius"},
    {AppCommand::Strength, "strength"},
    {AppCommand::Symmetry, "symmetry"},
    {AppCommand::View, "view"},
    {AppCommand::Screenshot, "screenshot"},
    {AppCommand::Preset, "preset"},
    {AppCommand::Grid, "grid"},
    {AppCommand::Recover, "recover"},
    {AppCommand::FramePiece, "frame_piece"},
}};

}  // namespace

std::optional<AppCommand> scriptCommandNamed(std::string_view name) {
  for (const auto& [command, n] : kScriptNames)
    if (name == n) return command;
  return std::nullopt;
}

const char* scriptCommandName(AppCommand command) {
  for (const auto& [c, n] : kScriptNames)
    if (c == command) return n;
  return nullptr;
}

std::vector<std::string> scriptCommandNames() {
  std::vector<std::string> names;
  for (const auto& entry : kScriptNames) names.emplace_back(entry.second);
  return names;
}

bool takesPath(AppCommand command) {
  switch (command) {
    case AppCommand::Open:
    case AppCommand::SaveProject:
    case AppCommand::SaveRecording:
    case AppCommand::Export:
    case AppCommand::ExportTets:
      return true;
    default:
      return false;
  }
}

std::optional<Command> keyCommand(int key, bool ctrl, bool shift, const std::string& projectFile) {
  if (ctrl) {
    switch (key) {
      case 'Z':
        return Command{shift ? AppCommand::Redo : AppCommand::Undo, ""};
      case 'Y':
        return Command{AppCommand::Redo, ""};
      case 'S':  // in place when a project is open; Shift: save as
        return Command{AppCommand::SaveProject, shift ? "" : projectFile};
      case 'O':
        return Command{AppCommand::Open, ""};
      case 'E':
        return Command{AppCommand::Export, ""};
      case 'Q':
        return Command{AppCommand::Quit, ""};
    }
    return std::nullopt;
  }
  for (const ToolRow& row : toolTable())
    if (key == row.key) return Command{AppCommand::Tool, row.label};
  switch (key) {
    case ' ':
      return Command{AppCommand::TogglePlay, ""};
    case '.':
      return Command{AppCommand::Step, ""};
    case '[':
      return Command{shift ? AppCommand::ScaleStrength : AppCommand::ScaleRadius, "0.8"};
    case ']':
      return Command{shift ? AppCommand::ScaleStrength : AppCommand::ScaleRadius, "1.25"};
    case 'X':
      return Command{AppCommand::ToggleSymmetry, ""};
    case 'F':
      return Command{shift ? AppCommand::FramePiece : AppCommand::FrameAll, ""};
    case '1':
      return Command{AppCommand::ViewFront, ""};
    case '3':
      return Command{AppCommand::ViewSide, ""};
    case '7':
      return Command{AppCommand::ViewTop, ""};
    case 'W':
      return Command{AppCommand::ToggleWireframe, ""};
    case 'V':
      return Command{AppCommand::CycleView, ""};
    case 'C':
      return Command{AppCommand::ToggleCrackTint, ""};
  }
  return std::nullopt;
}

}  // namespace galsculpt
