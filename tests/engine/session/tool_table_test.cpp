// The tool table (engine/session/tool_table.h): one row per tool, read by the window, the script
// reader and writer and the docs.
#include "engine/session/tool_table.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "engine/session/playback.h"
#include "solver/io/input_error.h"

namespace galsculpt {
namespace {

std::string readDoc(const char* name) {
  std::ifstream in(std::filesystem::path(GALSCULPT_SOURCE_DIR) / "docs" / name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ToolTable, NamesLabelsAndKeysAreUniqueAndFoundAgain) {
  std::set<std::string> names, labels;
  std::set<char> keys;
  int index = 0;
  for (const ToolRow& row : toolTable()) {
    EXPECT_EQ(static_cast<int>(row.tool), index++) << "rows in the enum's order";
    EXPECT_TRUE(names.insert(row.name).second) << row.name;
    EXPECT_TRUE(labels.insert(row.label).second) << row.label;
    EXPECT_TRUE(keys.insert(row.key).second) << row.key;
    EXPECT_EQ(toolNamed(row.name), row.tool);
    EXPECT_EQ(&toolRow(row.tool), &row);
  }
  EXPECT_EQ(index, 9);
  EXPECT_FALSE(toolNamed("anchor paint")) << "scripts name tools by their script names";
  EXPECT_EQ(toolNames(ToolKind::Brush), "grab, push, pull, inflate or pinch");
  EXPECT_EQ(toolNames(ToolKind::Paint), "anchor_paint or anchor_erase");
  EXPECT_EQ(toolNames(ToolKind::Knife), "knife");
}

// Each tool a script can hold is read under its name and written back under it.
TEST(ToolTable, EveryToolIsAScriptEventOfItsName) {
  for (const ToolRow& row : toolTable()) {
    if (row.kind == ToolKind::Navigate) {
      EXPECT_THROW(parseToolEvent(nlohmann::json{{"tool", row.name}}, "$", "t.json"), InputError)
          << "navigation is the window's alone";
      continue;
    }
    nlohmann::json event{{"tool", row.name}, {"frame", 2}};
    if (row.kind == ToolKind::Knife) {
      event["from"] = {{0, 1, 0}, {0, -1, 0}};
      event["to"] = {{1, 1, 0}, {1, -1, 0}};
    } else {
      event["center"] = {0, 0.1, 0};
      event["radius"] = 0.02;
    }
    const ToolEvent e = parseToolEvent(event, "$", "t.json");
    EXPECT_EQ(toolEventJson(e)["tool"], row.name) << row.name;
    EXPECT_EQ(e.stroke.kind, row.tool);
    if (row.kind == ToolKind::Paint) {
      EXPECT_EQ(e.erase(), row.tool == Tool::AnchorErase);
    }
  }
}

// The user guide's tool table has each tool's label and key; the scripts page a heading for
// each tool a script holds.
TEST(ToolTable, TheDocsListEveryTool) {
  const std::string guide = readDoc("user-guide.md");
  const std::string scripts = readDoc("scripts.md");
  for (const ToolRow& row : toolTable()) {
    const std::string line = "| " + std::string(row.label) + " | " + row.key + " |";
    EXPECT_NE(guide.find(line), std::string::npos) << "user-guide.md lacks " << line;
    if (row.kind == ToolKind::Navigate) continue;
    const std::string name = "`" + std::string(row.name) + "`";
    bool inHeading = false;
    std::istringstream lines(scripts);
    for (std::string l; std::getline(lines, l);)
      inHeading = inHeading || (l.rfind("### ", 0) == 0 && l.find(name) != std::string::npos);
    EXPECT_TRUE(inHeading) << "scripts.md has no heading naming " << name;
  }
}

}  // namespace
}  // namespace galsculpt
