// Every sculpting tool, declared once: its name in scripts, recordings and Python's apply(), its
// label in the window, the key that selects it, what kind of action it is and what it does. The
// window's tool list and keys, the script reader and writer, the brushes' names and the table of
// docs/scripts.md read this table (a test checks the docs against it), so a new brush is one row
// here and its effect (sculptor.cpp).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace galsculpt {

// What a tool's stroke does with the mouse: orbit the camera, cut along the blade it sweeps, move
// the vertices under the brush through the physics, or hold / free them (anchors).
enum class ToolKind { Navigate, Knife, Brush, Paint };

// X(id, name, label, key, kind, effect): the name scripts and Python use ("anchor_paint"), the
// window's label ("anchor paint"), the key, the kind, a line of what it does.
#define GALSCULPT_TOOLS(X)                                                             \
  X(Navigate, "navigate", "navigate", 'N', Navigate,                                   \
    "the left button orbits the camera, as the right button always does")              \
  X(Knife, "knife", "knife", 'K', Knife, "damages every edge the swept blade crosses") \
  X(Grab, "grab", "grab", 'G', Brush,                                                  \
    "holds the vertices under the brush and moves them with it, through the physics")  \
  X(Push, "push", "push", 'B', Brush, "presses the surface in along its normal")       \
  X(Pull, "pull", "pull", 'U', Brush, "draws the surface out along its normal")        \
  X(Inflate, "inflate", "inflate", 'I', Brush,                                         \
    "swells the surface from a point one radius below it")                             \
  X(Pinch, "pinch", "pinch", 'P', Brush, "draws the surface towards the brush's axis") \
  X(AnchorPaint, "anchor_paint", "anchor paint", 'A', Paint,                           \
    "holds the vertices within the radius where they are")                             \
  X(AnchorErase, "anchor_erase", "anchor erase", 'E', Paint,                           \
    "frees the vertices within the radius (scene anchors too)")

enum class Tool {
#define GALSCULPT_TOOL_ID(id, name, label, key, kind, effect) id,
  GALSCULPT_TOOLS(GALSCULPT_TOOL_ID)
#undef GALSCULPT_TOOL_ID
};

struct ToolRow {
  Tool tool;
  const char* name;   // in scripts and Python
  const char* label;  // in the window
  char key;
  ToolKind kind;
  const char* effect;
};

// The rows, in the window's order.
std::span<const ToolRow> toolTable();
const ToolRow& toolRow(Tool tool);
// The tool of a script name ("anchor_paint"), or none.
std::optional<Tool> toolNamed(std::string_view name);
// The script names of the tools of `kind`, for messages: "grab, push, pull, inflate or pinch".
std::string toolNames(ToolKind kind);

}  // namespace galsculpt
