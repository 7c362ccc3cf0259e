#include "app/window/window_panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>
#include <type_traits>
#include <vector>

#include "engine/session/simulation.h"
#include "solver/fem/material_table.h"
#include "solver/frame/parallel.h"
#include "solver/frame/timing.h"

namespace galsculpt {

namespace fs = std::filesystem;

namespace {

// A combo box over the values of a named enum (solver_options.h), shown by their names.
template <NamedEnum E>
void pickNamed(const char* label, E& value) {
  std::vector<const char*> names;
  int current = 0;
  for (const EnumName<E>& n : namesOf(value)) {
    if (n.value == value) current = static_cast<int>(names.size());
    names.push_back(n.name);
  }
  if (ImGui::Combo(label, &current, names.data(), static_cast<int>(names.size())))
    value = namesOf(value)[current].value;
}

// The widget of one solver option (solver/model/solver_options.h), by its type; numbers are
// held in the range a scene may give.
template <typename T>
void editOption(const OptionField<T>& f, T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    ImGui::Checkbox(f.label, &value);
  } else if constexpr (std::is_same_v<T, int>) {
    if (ImGui::InputInt(f.label, &value))
      value = std::clamp(value, static_cast<int>(f.min), static_cast<int>(f.max));
  } else if constexpr (std::is_same_v<T, double>) {
    if (ImGui::InputDouble(f.label, &value, 0.0, 0.0, "%.4g"))
      value = std::clamp(value, f.min, f.max);
  } else if constexpr (std::is_same_v<T, std::string>) {
    ImGui::InputText(f.label, &value);  // checked when applied (editScene)
  } else {
    pickNamed(f.label, value);
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("solver.%s", f.key);
}

// Every solver option; a preset picked sets the options in which the presets differ.
void editSolverOptions(SolverOptions& v) {
  SolverPreset preset = v.preset;
  pickNamed("solver preset", preset);
  if (preset != v.preset) {
    v.preset = preset;
    forEachSolverOption([&](const auto& f) {
      if (!(f.converged == f.paper)) v.*f.member = f.presetValue(preset);
    });
  }
  forEachSolverOption([&](const auto& f) { editOption(f, v.*f.member); });
}

// Wrap width of the overlay's free text, in pixels (its figures' lines are about this wide).
constexpr float kOverlayTextWidth = 340.0f;

}  // namespace

void WindowPanels::draw(PanelContext& c) {
  drawMenu(c);
  drawToolsPanel(c);
  drawScenePanel(c);
  drawOverlay(c);
  drawCursor(c);
  drawDialogs(c);
}

void WindowPanels::drawMenu(PanelContext& c) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    const bool open = c.session != nullptr;
    if (ImGui::MenuItem("Open...", "Ctrl+O")) c.execute({AppCommand::Open, ""});
    if (ImGui::MenuItem("Save project", "Ctrl+S", false, open))
      c.execute({AppCommand::SaveProject, c.projectFile.string()});
    if (ImGui::MenuItem("Save project as...", "Ctrl+Shift+S", false, open))
      c.execute({AppCommand::SaveProject, ""});
    if (ImGui::MenuItem("Save recording...", nullptr, false, open))
      c.execute({AppCommand::SaveRecording, ""});
    ImGui::Separator();
    if (ImGui::MenuItem("Export surface...", "Ctrl+E", false, open))
      c.execute({AppCommand::Export, ""});
    if (ImGui::MenuItem("Export tet mesh...", nullptr, false, open))
      c.execute({AppCommand::ExportTets, ""});
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) c.execute({AppCommand::Quit, ""});
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    const std::string undo =
        c.session && c.session->canUndo() ? "Undo " + c.session->undoLabel() : "Undo";
    const std::string redo =
        c.session && c.session->canRedo() ? "Redo " + c.session->redoLabel() : "Redo";
    if (ImGui::MenuItem(undo.c_str(), "Ctrl+Z", false, c.session && c.session->canUndo()))
      c.execute({AppCommand::Undo, ""});
    if (ImGui::MenuItem(redo.c_str(), "Ctrl+Shift+Z", false, c.session && c.session->canRedo()))
      c.execute({AppCommand::Redo, ""});
    if (ImGui::MenuItem("Reset to the start", nullptr, false, c.session != nullptr))
      c.execute({AppCommand::Reset, ""});
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Shaded", nullptr, c.style.view == SurfaceView::Shaded))
      c.style.view = SurfaceView::Shaded;
    if (ImGui::MenuItem("Damage", nullptr, c.style.view == SurfaceView::Damage))
      c.style.view = SurfaceView::Damage;
    if (ImGui::MenuItem("Stress", nullptr, c.style.view == SurfaceView::Stress))
      c.style.view = SurfaceView::Stress;
    ImGui::MenuItem("Wireframe", "W", &c.wireframe);
    ImGui::MenuItem("Tint crack faces", "C", &c.style.tintCracks);
    ImGui::Separator();
    if (ImGui::MenuItem("Frame", "F", false, c.session != nullptr))
      c.execute({AppCommand::FrameAll, ""});
    if (ImGui::MenuItem("Front", "1")) c.execute({AppCommand::ViewFront, ""});
    if (ImGui::MenuItem("Side", "3")) c.execute({AppCommand::ViewSide, ""});
    if (ImGui::MenuItem("Top", "7")) c.execute({AppCommand::ViewTop, ""});
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void WindowPanels::drawToolsPanel(PanelContext& c) {
  ImGui::SetNextWindowPos(ImVec2(10, 30), ImGuiCond_FirstUseEver);
  ImGui::Begin("Tools", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  for (const ToolRow& row : toolTable()) {
    const std::string label = std::string(row.label) + " (" + row.key + ")";
    if (ImGui::RadioButton(label.c_str(), c.tools.tool == row.tool))
      c.execute({AppCommand::Tool, row.label});
  }
  ImGui::Separator();
  float radius = static_cast<float>(c.tools.radius);
  if (ImGui::SliderFloat("radius (m)", &radius, 1e-4f, 1.0f, "%.4f", ImGuiSliderFlags_Logarithmic))
    c.tools.radius = radius;
  float strength = static_cast<float>(c.tools.strength);
  if (ImGui::SliderFloat("strength (m/s)", &strength, 1e-4f, 10.0f, "%.4f",
                         ImGuiSliderFlags_Logarithmic))
    c.tools.strength = strength;
  ImGui::Checkbox("symmetry (X)", &c.tools.symmetry);
  if (c.tools.symmetry) {
    ImGui::SameLine();
    const char* axes[] = {"x", "y", "z"};
    ImGui::SetNextItemWidth(50);
    ImGui::Combo("plane", &c.tools.symmetryAxis, axes, 3);
    float offset = static_cast<float>(c.tools.symmetryOffset);
    if (ImGui::InputFloat("offset (m)", &offset)) c.tools.symmetryOffset = offset;
  }
  ImGui::Separator();
  if (ImGui::Button(c.playing ? "Pause (space)" : "Play (space)"))
    c.execute({AppCommand::TogglePlay, ""});
  ImGui::SameLine();
  if (ImGui::Button("Step (.)")) c.execute({AppCommand::Step, ""});
  ImGui::SameLine();
  if (ImGui::Button("Reset")) c.execute({AppCommand::Reset, ""});
  const char* views[] = {"shaded", "damage", "stress"};
  int view = static_cast<int>(c.style.view);
  if (ImGui::Combo("view (V)", &view, views, 3)) c.style.view = static_cast<SurfaceView>(view);
  if (c.style.view == SurfaceView::Stress) {
    float scale = static_cast<float>(c.style.scaleMax);
    if (ImGui::SliderFloat("hottest (Pa)", &scale, 1.0f, 1e9f, "%.3g",
                           ImGuiSliderFlags_Logarithmic))
      c.style.scaleMax = scale;
  }
  ImGui::Checkbox("wireframe (W)", &c.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("tint cracks (C)", &c.style.tintCracks);
  ImGui::TextDisabled("left: tool   right: orbit   middle: pan   wheel: zoom");
  ImGui::End();
}

void WindowPanels::drawOverlay(PanelContext& c) {
  // Pinned by its top-right corner to the screen's: as its figures widen it grows leftwards,
  // never off the edge.
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 10, 30), ImGuiCond_Always,
                          ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::Begin("Simulation", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  // Long lines (a scene's name, a backend fallback's reason) wrap instead of widening it.
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + kOverlayTextWidth);
  // The rates are read four times a second, not at every draw: figures that change at every
  // draw cannot be read, and would make the window redraw the panel every time (on a software
  // rasterizer a panel that did not change is not drawn again). The frame's own figures below
  // are the drawn frame's.
  const WindowMeters::Overlay& r = c.meters.overlay();
  ImGui::Text("window %.0f fps (%.1f ms a frame on its thread)   simulation %.1f fps", r.windowFps,
              r.windowCpuMs, r.simulationFps);
  if (r.latencyMedianMs >= 0.0)
    ImGui::Text("input to screen %.0f ms (median; last %.0f ms)", r.latencyMedianMs,
                r.latencyLastMs);
  if (c.session) {
    // While a frame is in flight only what stays fixed is read from the session; the rest is
    // the drawn frame's (c.shown).
    const Simulation& sim = c.session->simulation();
    const SceneDescription& scene = c.session->scene();
    const FrameMetrics& m = c.shown.metrics;
    ImGui::Text("%s: %d vertices, %d tets", scene.name.c_str(), sim.model().numVertices(),
                sim.model().numTets());
    ImGui::Text("material: %s (%s)", scene.material.preset.c_str(),
                materialModelName(scene.material.model));
    ImGui::Text("solver: %s (%s) %s on the %s backend, %d threads", enumName(scene.solver.type),
                enumName(scene.solver.preset), scene.solver.grid.c_str(),
                c.shown.backendName.c_str(), threadCount());
    ImGui::Separator();
    ImGui::Text("frame %d  (%s)", m.frame, c.playing ? "playing" : "paused");
    ImGui::Text("ms: total %.1f  elements %.1f  solve %.1f", m.msTotal, m.msElements, m.msSolve);
    ImGui::Text("    fracture %.1f  plastic %.1f  surface %.1f", m.msFracture, m.msPlastic,
                c.shown.msSurface);
    // (local: of the Newton iterations, those that solved only where the residual was)
    ImGui::Text("residual %.2e   Newton %d (local %d)   CG %d", m.residual, m.newtonIterations,
                m.localIterations, m.cgIterations);
    if (!m.converged)
      ImGui::TextColored(ImVec4(1, 0.35f, 0.2f, 1),
                         "NOT CONVERGED: a residual above %.0e of its loads",
                         scene.solver.residualTolerance);
    // The body's norm can hide a piece's (docs/physics.md): said here; with
    // solver.converge_pieces (the default) such a frame is also not converged.
    if (pieceAboveTolerance(m, scene.solver.residualTolerance))
      ImGui::TextColored(ImVec4(1, 0.6f, 0.2f, 1), "worst piece's residual %.2e of its own loads",
                         m.pieceResidual);
    if (m.invertedElements > 0)
      ImGui::TextColored(ImVec4(1, 0.6f, 0.2f, 1), "%d elements inside out", m.invertedElements);
    ImGui::Text("volume change %+.3f %%", m.volumeChangePct);
    ImGui::Text("pieces %d   damaged edges %d   anchored %zu", m.pieces, m.damagedEdges,
                c.shown.anchors.size());
    if (m.warnings > 0)
      ImGui::TextColored(ImVec4(1, 0.6f, 0.2f, 1), "warnings this frame: %d", m.warnings);
    ImGui::Text("history %.1f MB, %zu recorded events", c.shown.historyBytes / 1048576.0,
                c.shown.recordedEvents);
    for (const std::string& note : c.shown.notes) ImGui::TextDisabled("%s", note.c_str());
  }
  if (!status_.empty()) ImGui::TextDisabled("%s", status_.c_str());
  ImGui::PopTextWrapPos();
  ImGui::End();
}

void WindowPanels::drawScenePanel(PanelContext& c) {
  if (!c.session) return;
  ImGui::SetNextWindowPos(ImVec2(10, 470), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
  ImGui::Begin("Scene settings", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  MaterialDesc& m = editing_.material;
  std::vector<const char*> presets;
  for (const std::string& name : materialPresetNames()) presets.push_back(name.c_str());
  int preset = 0;
  for (size_t i = 0; i < presets.size(); ++i)
    if (m.preset == presets[i]) preset = static_cast<int>(i);
  if (ImGui::Combo("preset", &preset, presets.data(), static_cast<int>(presets.size())))
    m = materialPreset(presets[preset]);
  {
    int current = 0;
    const char* names[std::size(kMaterialModels)];
    for (size_t k = 0; k < std::size(kMaterialModels); ++k) {
      names[k] = kMaterialModels[k].name;
      if (kMaterialModels[k].model == m.model) current = static_cast<int>(k);
    }
    if (ImGui::Combo("model", &current, names, static_cast<int>(std::size(names))))
      m.model = kMaterialModels[current].model;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", kMaterialModels[current].summary);
  }
  ImGui::InputDouble("Young's modulus (Pa)", &m.youngsModulus, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("Poisson ratio", &m.poissonRatio, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("density (kg/m^3)", &m.density, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("yield stress (Pa, 0: elastic)", &m.yieldStress, 0.0, 0.0, "%.4g");
  ImGui::InputDouble("hardening (Pa)", &m.hardening, 0.0, 0.0, "%.4g");
  ImGui::Checkbox("fracture", &editing_.fracture);
  if (editing_.fracture)
    ImGui::InputDouble("threshold (Pa, 0: material's)", &editing_.fractureThreshold, 0.0, 0.0,
                       "%.4g");
  ImGui::Separator();
  editSolverOptions(editing_.solver);
  if (ImGui::Button("Apply (restarts the simulation)")) apply_ = true;  // between frames
  ImGui::SameLine();
  if (ImGui::Button("Revert")) {
    editing_ = sceneSettings(c.session->scene());
  }
  ImGui::End();
}

// The tool's preview, at the newest cursor sample and against the drawn surface, so that it
// follows the cursor at the window's rate however long a frame takes.
void WindowPanels::drawCursor(PanelContext& c) {
  if (!c.controller || (ImGui::GetIO().WantCaptureMouse && !c.scripted)) return;
  int width = 1, height = 1;
  glfwGetWindowSize(c.window, &width, &height);
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const float x = static_cast<float>(cursorX_), y = static_cast<float>(cursorY_);
  if (c.tools.tool == Tool::Knife) {
    // The stroke so far (the blade's path on the screen), then the knife at the cursor.
    for (size_t k = 1; k < trail_.size(); ++k)
      draw->AddLine(ImVec2(trail_[k - 1].first, trail_[k - 1].second),
                    ImVec2(trail_[k].first, trail_[k].second), IM_COL32(255, 80, 60, 200), 2.0f);
    draw->AddLine(ImVec2(x - 8, y + 8), ImVec2(x + 8, y - 8), IM_COL32(255, 80, 60, 255), 2.0f);
    return;
  }
  const std::optional<RayHit> hit = hoverShown(c, width, height);
  if (!hit) return;
  // The brush radius on screen: project a point one radius away on the plane facing the camera.
  const Vec3 side = c.camera.forward().cross(Vec3::UnitY()).normalized();
  const Vec3 centre = c.camera.project(hit->point, width, height);
  const Vec3 r = c.camera.project(hit->point + c.tools.radius * side, width, height);
  const float pixels = static_cast<float>((r - centre).head<2>().norm());
  const ImU32 color = toolRow(c.tools.tool).kind == ToolKind::Paint ? IM_COL32(60, 110, 255, 255)
                                                                    : IM_COL32(255, 255, 255, 220);
  draw->AddCircle(ImVec2(float(centre.x()), float(centre.y())), pixels, color, 48, 1.5f);
  if (c.tools.symmetry) {
    const Symmetry plane{c.tools.symmetryAxis, c.tools.symmetryOffset};
    const Vec3 m = c.camera.project(plane.point(hit->point), width, height);
    draw->AddCircle(ImVec2(float(m.x()), float(m.y())), pixels, IM_COL32(255, 255, 255, 110), 48,
                    1.0f);
  }
}

// The drawn surface's point under the cursor (none for the knife and navigation).
std::optional<RayHit> WindowPanels::hoverShown(const PanelContext& c, int width, int height) {
  const ToolKind kind = toolRow(c.tools.tool).kind;
  if (!c.shown.valid || kind == ToolKind::Navigate || kind == ToolKind::Knife) return std::nullopt;
  Vec3 origin, direction;
  c.camera.ray(cursorX_, cursorY_, width, height, origin, direction);
  return shownPicker_.intersect(c.shown.surface, c.shown.damageRevision, c.shown.generation, origin,
                                direction);
}

void WindowPanels::drawDialogs(PanelContext& c) {
  if (c.opener.busy()) {
    ImGui::OpenPopup("Loading");
  }
  if (ImGui::BeginPopupModal("Loading", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    const char spinner[] = "|/-\\";
    ImGui::Text("%c %s", spinner[static_cast<int>(ImGui::GetTime() * 8) % 4],
                c.opener.progress().c_str());
    if (!c.opener.busy()) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (showError_) {
    ImGui::OpenPopup("Error");
    showError_ = false;
  }
  if (ImGui::BeginPopupModal("Error", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::TextUnformatted(error_.c_str());
    if (ImGui::Button("OK") || c.scripted) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  drawRecoveryDialog(c);
  drawPathDialog(c);
}

void WindowPanels::drawRecoveryDialog(PanelContext& c) {
  if (askRecovery_ && !c.opener.busy()) {
    ImGui::OpenPopup("Recover");
    askRecovery_ = false;
  }
  if (ImGui::BeginPopupModal("Recover", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("Galsculpt did not close normally. Recover the autosaved work?");
    ImGui::TextDisabled("%s", recoverable_.front().string().c_str());
    if (ImGui::Button("Recover")) {
      c.execute({AppCommand::Open, recoverable_.front().string()});
      // Keep the file until the recovered work is saved elsewhere or autosaved anew.
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Discard")) {
      for (const fs::path& f : recoverable_) c.recovery.remove(f);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Later")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

// The path dialog of a file command (Open, Save project, ...) that came without a path.
void WindowPanels::drawPathDialog(PanelContext& c) {
  // Titles, hints and default names, by AppCommand::Open .. ExportTets.
  struct Kind {
    AppCommand command;
    const char *title, *hint, *suffix;
  };
  static const Kind kinds[] = {
      {AppCommand::Open, "Open", "a project (.gsproj), scene (.json) or mesh", ""},
      {AppCommand::SaveProject, "Save project", "a .gsproj file", ".gsproj"},
      {AppCommand::SaveRecording, "Save recording", "a .json playback script", "-recording.json"},
      {AppCommand::Export, "Export surface", ".obj, .ply, .stl, .gltf or .glb", ".obj"},
      {AppCommand::ExportTets, "Export tet mesh",
       "a path without extension (writes .node/.ele/.face/.damage/.vtk)", "-tets"},
  };
  if (!askingPath_) return;
  const Kind* kind = nullptr;
  for (const Kind& k : kinds)
    if (k.command == *askingPath_) kind = &k;
  if (!kind) return;
  ImGui::OpenPopup("Path");
  if (path_[0] == '\0') {
    const std::string stem = c.session ? c.session->scene().name : "galsculpt";
    const std::string guess =
        kind->command == AppCommand::Open ? c.currentFile.string() : stem + kind->suffix;
    std::snprintf(path_, sizeof path_, "%s", guess.c_str());
  }
  if (ImGui::BeginPopupModal("Path", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s: %s", kind->title, kind->hint);
    ImGui::SetNextItemWidth(520);
    const bool enter =
        ImGui::InputText("##path", path_, sizeof path_, ImGuiInputTextFlags_EnterReturnsTrue);
    const bool ok = ImGui::Button("OK") || enter;
    ImGui::SameLine();
    const bool cancel = ImGui::Button("Cancel");
    if (ok || cancel) {
      const Command chosen{kind->command, path_};
      askingPath_.reset();
      path_[0] = '\0';
      ImGui::CloseCurrentPopup();
      if (ok && !chosen.argument.empty()) c.execute(chosen);
    }
    ImGui::EndPopup();
  }
}

void WindowPanels::cursorAt(double x, double y) {
  cursorX_ = x;
  cursorY_ = y;
  if (trailing_) trail_.emplace_back(static_cast<float>(x), static_cast<float>(y));
}

void WindowPanels::knifeStroke(bool drawing) {
  trailing_ = drawing;
  trail_.clear();
  if (trailing_) trail_.emplace_back(static_cast<float>(cursorX_), static_cast<float>(cursorY_));
}

}  // namespace galsculpt
