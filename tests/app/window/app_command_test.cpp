#include "app/window/app_command.h"

#include <gtest/gtest.h>

#include "app/window/tool_controller.h"

namespace galsculpt {
namespace {

TEST(AppCommand, ScriptNamesRoundTripAndUnknownNamesAreRefused) {
  const std::vector<std::string> names = scriptCommandNames();
  EXPECT_EQ(names.size(), 21u) << "the names scripts may use (docs/user-guide.md)";
  for (const std::string& name : names) {
    const std::optional<AppCommand> c = scriptCommandNamed(name);
    ASSERT_TRUE(c) << name;
    EXPECT_EQ(scriptCommandName(*c), name);
  }
  EXPECT_FALSE(scriptCommandNamed("format_disk"));
  EXPECT_FALSE(scriptCommandNamed("Save_Project")) << "names are exact";
  EXPECT_EQ(scriptCommandName(AppCommand::TogglePlay), nullptr) << "a key's shortcut only";
}

TEST(AppCommand, KeysMapToTheCommandsTheGuideDocuments) {
  auto key = [](int k, bool ctrl = false, bool shift = false, const std::string& project = "") {
    return keyCommand(k, ctrl, shift, project);
  };
  EXPECT_EQ(key('Z', true)->kind, AppCommand::Undo);
  EXPECT_EQ(key('Z', true, true)->kind, AppCommand::Redo);
  EXPECT_EQ(key('Y', true)->kind, AppCommand::Redo);
  // Ctrl+S saves the open project in place; without one, or with Shift, it asks for a path.
  EXPECT_EQ(key('S', true, false, "a.gsproj")->argument, "a.gsproj");
  EXPECT_EQ(key('S', true, true, "a.gsproj")->argument, "");
  EXPECT_TRUE(takesPath(key('S', true)->kind));
  EXPECT_EQ(key('O', true)->kind, AppCommand::Open);
  EXPECT_EQ(key('Q', true)->kind, AppCommand::Quit);
  EXPECT_EQ(key(' ')->kind, AppCommand::TogglePlay);
  EXPECT_EQ(key('.')->kind, AppCommand::Step);
  EXPECT_EQ(key('[')->kind, AppCommand::ScaleRadius);
  EXPECT_EQ(key(']', false, true)->kind, AppCommand::ScaleStrength);
  EXPECT_EQ(key(']', false, true)->argument, "1.25");
  EXPECT_EQ(key('F')->kind, AppCommand::FrameAll);
  EXPECT_EQ(key('F', false, true)->kind, AppCommand::FramePiece);
  for (const ToolRow& row : toolTable()) {
    const std::optional<Command> c = key(row.key);
    ASSERT_TRUE(c) << row.label;
    EXPECT_EQ(c->kind, AppCommand::Tool);
    EXPECT_EQ(c->argument, row.label);
  }
  EXPECT_FALSE(key('Q')) << "Q alone does nothing";
  EXPECT_FALSE(key('A', true));
}

}  // namespace
}  // namespace galsculpt
