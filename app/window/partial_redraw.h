// Partial redraws for a window whose back buffer still holds its previous draw (a software
// rasterizer, where every pixel drawn costs the CPU the simulation runs on): only the parts of
// the screen that changed are copied from the scene's cache and drawn over with the panels.
//
// Each of ImGui's draw lists (a panel, the overlay, the cursor's circle) is compared with what
// it drew last time. A list is drawn again when it changed, or when something drawn again
// beneath or over it overlaps it: the part of the screen under it is restored from the scene
// first, since panels blend over what is there. Unchanged lists clear of all that keep their
// pixels.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/render/pixel_rect.h"

struct ImDrawData;
struct ImDrawList;

namespace galsculpt {

struct RedrawPlan {
  std::vector<PixelRect> restore;  // parts of the scene to copy to the screen first
  std::vector<int> lists;          // the draw lists to draw again, in ImGui's order
};

class PanelRedraws {
 public:
  // The plan for this draw, given where the scene changed since the last one; remembers the
  // lists as drawn. `full`: the screen holds nothing usable (a first draw, a resize, a back
  // buffer that is not the previous draw): everything is restored and drawn.
  RedrawPlan plan(const ImDrawData& data, const PixelRect& sceneChanged, int width, int height,
                  bool full);

 private:
  struct Drawn {
    const ImDrawList* list = nullptr;
    std::uint64_t hash = 0;
    PixelRect rect;
  };
  std::vector<Drawn> last_;
};

// ImGui's draw data with only the given lists (for ImGui_ImplOpenGL3_RenderDrawData); it refers
// to `data`'s lists and must not outlive them.
class DrawDataSubset {
 public:
  DrawDataSubset(const ImDrawData& data, const std::vector<int>& lists);
  ~DrawDataSubset();
  ImDrawData* get() { return data_; }

 private:
  std::vector<ImDrawList*> lists_;
  ImDrawData* data_;
};

}  // namespace galsculpt
