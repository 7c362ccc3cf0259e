#include "engine/session/tool_table.h"

namespace galsculpt {

namespace {

constexpr ToolRow kTools[] = {
#define GALSCULPT_TOOL_ROW(id, name, label, key, kind, effect) \
  {Tool::id, name, label, key, ToolKind::kind, effect},
    GALSCULPT_TOOLS(GALSCULPT_TOOL_ROW)
#undef GALSCULPT_TOOL_ROW
};

}  // namespace

std::span<const ToolRow> toolTable() {
  return kTools;
}

const ToolRow& toolRow(Tool tool) {
  return kTools[static_cast<int>(tool)];
}

std::optional<Tool> toolNamed(std::string_view name) {
  for (const ToolRow& row : kTools)
    if (name == row.name) return row.tool;
  return std::nullopt;
}

std::string toolNames(ToolKind kind) {
  std::string names, last;
  for (const ToolRow& row : kTools) {
    if (row.kind != kind) continue;
    if (!last.empty()) names += (names.empty() ? "" : ", ") + last;
    last = row.name;
  }
  return names.empty() ? last : names + " or " + last;
}

}  // namespace galsculpt
