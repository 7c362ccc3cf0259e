#include "engine/session/sculpt_session.h"

#include <algorithm>
#include <limits>

#include "solver/io/atomic_file.h"
#include "solver/io/input_error.h"
#include "solver/io/stop_request.h"

namespace galsculpt {

SculptSession::SculptSession(const SceneDescription& scene, const TetMesh& mesh)
    : scene_(scene),
      sim_(std::make_unique<Simulation>(scene, mesh)),
      tools_(std::make_unique<ToolApplier>(*sim_, scene.file.string())),
      initial_(sim_->snapshot()) {}

void SculptSession::record(ToolEvent e) {
  e.frame = sim_->frame();
  e.path = "$.events[" + std::to_string(recording_.size()) + "]";
  if (e.kind != ToolEvent::Kind::Camera) dirty_ = true;  // a view alone is no reason to save
  recording_.push_back(std::move(e));
}

void SculptSession::beginAction(const std::string& label) {
  endStroke();
  Step s;
  s.label = label;
  s.state = sim_->snapshot();
  s.keep = recording_.size();
  historyBytes_ += s.bytes();
  undo_.push_back(std::move(s));
  for (const Step& r : redo_) historyBytes_ -= r.bytes();
  redo_.clear();
  trimHistory();
}

int SculptSession::knife(const Vec3& from0, const Vec3& from1, const Vec3& to0, const Vec3& to1,
                         const Symmetry& symmetry) {
  ToolEvent e;
  e.kind = ToolEvent::Kind::Knife;
  e.stroke.kind = Tool::Knife;
  e.from0 = from0;
  e.from1 = from1;
  e.to0 = to0;
  e.to1 = to1;
  e.stroke.symmetry = symmetry;
  e.frame = sim_->frame();
  const int cut = tools_->apply(e, e.frame);
  record(e);
  return cut;
}

void SculptSession::beginStroke(const BrushStroke& stroke) {
  endStroke();
  ToolEvent e;
  e.kind = ToolEvent::Kind::Stroke;
  e.stroke = stroke;
  e.frame = sim_->frame();
  e.end = std::numeric_limits<int>::max();  // open until endStroke
  tools_->apply(e, e.frame);
  record(e);
  strokeEvent_ = static_cast<int>(recording_.size()) - 1;
}

void SculptSession::moveStroke(const Vec3& center, const Vec3& normal) {
  if (strokeEvent_ < 0) return;
  tools_->sculptor().moveBrush(center, normal);
  recording_[strokeEvent_].moves.push_back({sim_->frame(), center, normal});
  dirty_ = true;
}

void SculptSession::endStroke() {
  if (strokeEvent_ < 0) return;
  tools_->sculptor().endBrush();
  recording_[strokeEvent_].end = sim_->frame();
  strokeEvent_ = -1;
}

int SculptSession::paint(const Vec3& center, double radius, int seed, bool erase,
                         const Symmetry& symmetry) {
  ToolEvent e;
  e.kind = ToolEvent::Kind::Paint;
  e.stroke.center = center;
  e.stroke.radius = radius;
  e.stroke.seed = seed;
  e.stroke.kind = erase ? Tool::AnchorErase : Tool::AnchorPaint;
  e.stroke.symmetry = symmetry;
  const int changed = tools_->sculptor().paintAnchors(center, radius, seed, erase, symmetry);
  record(e);
  return changed;
}

void SculptSession::setCamera(const CameraPose& pose) {
  if (!recording_.empty()) {
    ToolEvent& last = recording_.back();
    if (last.kind == ToolEvent::Kind::Camera && last.frame == sim_->frame()) {
      last.camera = pose;
      return;
    }
  }
  ToolEvent e;
  e.kind = ToolEvent::Kind::Camera;
  e.camera = pose;
  record(e);
}

namespace {

// The last frame before which a script's event acts (ToolApplier::apply); a brush's release is
// its anchor's, in the state.
int lastActingFrame(const ToolEvent& e) {
  if (e.kind == ToolEvent::Kind::Knife) return e.frame + e.duration - 1;
  if (e.kind == ToolEvent::Kind::Stroke) return e.end;
  return e.frame;
}

}  // namespace

void SculptSession::apply(ToolEvent event, const std::string& source) {
  checkToolEvent(event, *sim_, source);
  if (event.kind == ToolEvent::Kind::Anchor && !event.add) {
    if (event.sceneAnchor >= static_cast<int>(scene_.anchors.size()))
      throw InputError(source, 0,
                       event.path + ".scene_anchor: the scene has " +
                           std::to_string(scene_.anchors.size()) + " anchor(s)");
    const bool toBeAdded = std::any_of(acting_.begin(), acting_.end(), [&](const ToolEvent& e) {
      return e.kind == ToolEvent::Kind::Anchor && e.add && e.name == event.name;
    });
    if (!event.name.empty() && !sim_->anchors().named(event.name) && !toBeAdded)
      throw InputError(source, 0,
                       event.path + ".name: no anchor named \"" + event.name + "\" holds now");
  }
  beginAction("apply");
  event.scripted = true;
  record(event);
  acting_.push_back(recording_.back());
}

FrameMetrics SculptSession::step() {
  // The user's events were applied as they came; those given to apply() act as in a script.
  const int idleBefore = tools_->idleCount();
  tools_->prepareFrame(acting_, sim_->frame());
  dirty_ = true;
  FrameMetrics m = sim_->advance();
  m.idleTools = tools_->idleCount() - idleBefore;
  std::erase_if(acting_, [&](const ToolEvent& e) { return lastActingFrame(e) < sim_->frame(); });
  return m;
}

void SculptSession::reset() {
  beginAction("reset");
  Step& step = undo_.back();  // undoing the reset brings the whole recording back
  step.keep = 0;
  step.append = std::move(recording_);
  historyBytes_ += step.append.size() * sizeof(ToolEvent);
  tools_ = std::make_unique<ToolApplier>(*sim_, scene_.file.string());
  acting_.clear();
  sim_->restore(initial_);
  recording_.clear();
  dirty_ = true;
}

void SculptSession::setState(const std::vector<Vec3>* x, const std::vector<Vec3>* v) {
  sim_->checkPositionsAndVelocities(x, v);  // refused before anything changes
  beginAction("set state");
  sim_->setPositionsAndVelocities(x, v);
  dirty_ = true;
}

const std::string& SculptSession::undoLabel() const {
  static const std::string none;
  return undo_.empty() ? none : undo_.back().label;
}

const std::string& SculptSession::redoLabel() const {
  static const std::string none;
  return redo_.empty() ? none : redo_.back().label;
}

SculptSession::Step SculptSession::travel(Step target) {
  Step back;
  back.label = target.label;
  back.state = sim_->snapshot();
  back.keep = std::min(target.keep, recording_.size());
  back.append.assign(recording_.begin() + static_cast<long>(back.keep), recording_.end());
  recording_.resize(back.keep);
  recording_.insert(recording_.end(), std::make_move_iterator(target.append.begin()),
                    std::make_move_iterator(target.append.end()));
  sim_->restore(target.state);
  tools_ = std::make_unique<ToolApplier>(*sim_, scene_.file.string());
  // The script's events of the recording that still act after the frame travelled to, as a
  // replay of the recording would apply them.
  acting_.clear();
  for (const ToolEvent& e : recording_)
    if (e.scripted && lastActingFrame(e) >= sim_->frame()) acting_.push_back(e);
  dirty_ = true;
  return back;
}

bool SculptSession::moveAcross(std::deque<Step>& from, std::deque<Step>& to) {
  endStroke();
  if (from.empty()) return false;
  Step target = std::move(from.back());
  from.pop_back();
  historyBytes_ -= target.bytes();
  Step back = travel(std::move(target));
  historyBytes_ += back.bytes();
  to.push_back(std::move(back));
  return true;
}

bool SculptSession::undo() {
  return moveAcross(undo_, redo_);
}

bool SculptSession::redo() {
  return moveAcross(redo_, undo_);
}

void SculptSession::setHistoryBudget(std::size_t bytes) {
  historyBudget_ = bytes;
  trimHistory();
}

void SculptSession::trimHistory() {
  // The oldest steps go first; the newest undo step always stays, even over the budget.
  while (historyBytes_ > historyBudget_ && undo_.size() > 1) {
    historyBytes_ -= undo_.front().bytes();
    undo_.pop_front();
  }
  while (historyBytes_ > historyBudget_ && !redo_.empty()) {
    historyBytes_ -= redo_.front().bytes();
    redo_.pop_front();
  }
}

std::vector<ToolEvent> SculptSession::recordingSoFar() const {
  std::vector<ToolEvent> events = recording_;
  if (strokeEvent_ >= 0) events[strokeEvent_].end = sim_->frame();  // a held stroke ends here
  return events;
}

void SculptSession::saveRecording(const std::filesystem::path& file) const {
  std::filesystem::path scene = scene_.file;
  if (sceneEdited_) {
    scene = file;
    scene.replace_extension(".scene.json");
    const std::string text = scene_.source.dump(1) + "\n";
    writeFileAtomically(scene, [&](std::ostream& out) { out << text; });
  }
  writePlaybackScript(file, scene, sim_->frame(), recordingSoFar());
}

void SculptSession::replay(const PlaybackScript& script,
                           const std::function<void(int, int)>& progress) {
  tools_ = std::make_unique<ToolApplier>(*sim_, script.file.string());
  acting_.clear();
  checkScriptAnchors(script, *sim_);
  while (sim_->frame() < script.frames) {
    throwIfStopRequested();  // Ctrl-C or SIGTERM during `open --headless`
    tools_->prepareFrame(script.events, sim_->frame());  // as Playback::advance
    sim_->advance();
    if (progress) progress(sim_->frame(), script.frames);
  }
  tools_->applyTrailing(script.events, sim_->frame());  // as Playback::advance at the end
  // What reaches past the script's end (a stroke's later moves and its release, a knife's later
  // sweeps) acts on in the session's frames as a replay of its recording applies it.
  for (const ToolEvent& e : script.events)
    if (lastActingFrame(e) >= sim_->frame()) acting_.push_back(e);
  recording_ = script.events;
  dirty_ = true;
}

void SculptSession::load(const SimulationSnapshot& state, std::vector<ToolEvent> recording) {
  strokeEvent_ = -1;
  sim_->restore(state);
  tools_ = std::make_unique<ToolApplier>(*sim_, scene_.file.string());
  acting_.clear();
  recording_ = std::move(recording);
  undo_.clear();
  redo_.clear();
  historyBytes_ = 0;
  dirty_ = false;
}

}  // namespace galsculpt
