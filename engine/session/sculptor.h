// The sculpting tools' effect on a running simulation: the knife, the deformation brushes
// (grab, push, pull, inflate, pinch) and anchor paint / erase, each optionally mirrored across a
// symmetry plane. The app drives it from the mouse, playback from scripts: both make the same
// calls at the same frames, so a recorded session replays exactly (engine/session/playback.h).
//
// Brushes act through the physics, never on the surface alone: they hold the vertices under
// the brush and move them; the solver moves the rest, so volume is kept where the material
// keeps it, clay keeps a dent and rubber springs back once the brush lets go. The shaping
// brushes weigh each vertex by w = (1 - (d / r)^2)^2 of its distance d from the centre, and
// hold it by a spring of that weight (a soft anchor, AnchorConstraint::springWeights): stiff
// at the centre, nothing at the rim, so the vertices they select anew each frame are not
// switched between held and free. The grab holds its vertices exactly (Dirichlet).
//   - grab: the vertices within the radius (of the piece under the cursor) follow the cursor
//     together, as if held in a hand; the falloff around them is the physics' (a falloff imposed
//     inside the held region would strain it and, on a brittle body, tear it there);
//   - push / pull: while the button is held, each frame moves the vertices under the brush by
//     w * strength * dt against / along the surface normal;
//   - inflate: the same, each vertex away from a point one radius below the surface;
//   - pinch: the same, towards the brush's axis.
// A brush that moves faster than its radius per frame covers the whole segment it swept (the
// capsule around it), so fast strokes are interpolated, never dropped.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/session/simulation.h"
#include "engine/session/tool_table.h"
#include "solver/fracture/knife.h"

namespace galsculpt {

// Mirror plane: coordinate `axis` (0 x, 1 y, 2 z) equal to `offset`; axis -1: no symmetry.
struct Symmetry {
  int axis = -1;
  double offset = 0.0;
  bool enabled() const { return axis >= 0; }
  Vec3 point(const Vec3& p) const;
  Vec3 direction(const Vec3& d) const;
};

struct BrushStroke {
  // A brush of the tool table (ToolKind::Brush); in a ToolEvent also the knife or anchor paint.
  Tool kind = Tool::Grab;
  Vec3 center = Vec3::Zero();   // on the surface, current positions
  Vec3 normal = Vec3::UnitY();  // outward surface normal at the centre
  double radius = 0.01;         // m
  double strength = 0.1;        // m/s for push, pull, inflate and pinch; unused by grab
  int seed = -1;                // a vertex of the piece to act on; -1: the vertex nearest centre
  Symmetry symmetry;
};

class Sculptor {
 public:
  explicit Sculptor(Simulation& sim) : sim_(sim) {}

  // Damages every edge the blade surface crosses (and its mirror image); returns how many.
  int cut(const std::vector<BladeTriangle>& blade, const Symmetry& symmetry);

  void beginBrush(const BrushStroke& stroke);
  void moveBrush(const Vec3& center, const Vec3& normal);
  void endBrush();
  bool brushActive() const { return !sides_.empty(); }
  // Vertices the stroke under way has held so far, over its frames (0: it reached nothing).
  int strokeReach() const { return strokeReach_; }
  // Before each frame: push, pull, inflate and pinch move what they hold.
  void beforeFrame();

  // Anchors (erase: frees) the vertices within `radius` of `center` in the seed's piece (and
  // their mirror images); returns how many vertices changed.
  int paintAnchors(const Vec3& center, double radius, int seed, bool erase,
                   const Symmetry& symmetry);

  // Vertices within `radius` of segment [a, b] in the piece of `seed` (-1: nearest to b), with
  // their brush weights.
  void selectUnderBrush(const Vec3& a, const Vec3& b, double radius, int seed,
                        std::vector<int>& vertices, std::vector<double>& weights) const;

 private:
  struct Side {
    int seed = -1;
    bool mirrored = false;
    Vec3 startCenter, previousCenter, center, normal;
    std::vector<int> vertices;
    std::vector<double> weights;
    std::vector<Vec3> start;  // grab: where the held vertices were when it began
    // Push, pull, inflate, pinch: each vertex under the brush's target, moved on by its step every
    // frame from where it was, not from where the vertex lags behind it (a spring's lag does not
    // add up frame after frame); a vertex that leaves the brush drops its target.
    std::map<int, Vec3> targets;
    int anchor = -1;
  };
  Vec3 brushDirection(const Side& side, const Vec3& x, const Vec3& nearest) const;

  Simulation& sim_;
  BrushStroke stroke_;
  std::vector<Side> sides_;  // the stroke and, with symmetry, its mirror image
  int strokeReach_ = 0;
};

}  // namespace galsculpt
