#include "app/window/partial_redraw.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace galsculpt {

namespace {

std::uint64_t mix(std::uint64_t h, const void* bytes, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(bytes);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

// What a list draws, to the byte: its vertices, indices and commands.
std::uint64_t contentHash(const ImDrawList& list) {
  std::uint64_t h = 1469598103934665603ull;
  h = mix(h, list.VtxBuffer.Data, sizeof(ImDrawVert) * list.VtxBuffer.Size);
  h = mix(h, list.IdxBuffer.Data, sizeof(ImDrawIdx) * list.IdxBuffer.Size);
  for (const ImDrawCmd& c : list.CmdBuffer) {
    h = mix(h, &c.ClipRect, sizeof c.ClipRect);
    h = mix(h, &c.TextureId, sizeof c.TextureId);
    h = mix(h, &c.VtxOffset, sizeof c.VtxOffset);
    h = mix(h, &c.IdxOffset, sizeof c.IdxOffset);
    h = mix(h, &c.ElemCount, sizeof c.ElemCount);
    const bool callback = c.UserCallback != nullptr;
    h = mix(h, &callback, sizeof callback);
  }
  return h;
}

// The pixels a list can touch: its vertices' extent within its commands' clip rectangles, in
// framebuffer pixels with row 0 at the bottom, grown by a pixel for rounding.
PixelRect listRect(const ImDrawList& list, const ImDrawData& data, int width, int height) {
  if (list.VtxBuffer.Size == 0) return {};
  float vx0 = 1e30f, vy0 = 1e30f, vx1 = -1e30f, vy1 = -1e30f;
  for (const ImDrawVert& v : list.VtxBuffer) {
    vx0 = std::min(vx0, v.pos.x), vy0 = std::min(vy0, v.pos.y);
    vx1 = std::max(vx1, v.pos.x), vy1 = std::max(vy1, v.pos.y);
  }
  float cx0 = 1e30f, cy0 = 1e30f, cx1 = -1e30f, cy1 = -1e30f;
  for (const ImDrawCmd& c : list.CmdBuffer) {
    cx0 = std::min(cx0, c.ClipRect.x), cy0 = std::min(cy0, c.ClipRect.y);
    cx1 = std::max(cx1, c.ClipRect.z), cy1 = std::max(cy1, c.ClipRect.w);
  }
  const float x0 = std::max(vx0, cx0), y0 = std::max(vy0, cy0);
  const float x1 = std::min(vx1, cx1), y1 = std::min(vy1, cy1);
  if (x1 <= x0 || y1 <= y0) return {};
  const ImVec2 o = data.DisplayPos, s = data.FramebufferScale;
  const auto px = [](float v) { return static_cast<int>(std::clamp(v, -1e6f, 1e6f)); };
  // ImGui counts rows from the top; GL from the bottom.
  return PixelRect{px(std::floor((x0 - o.x) * s.x)), px(height - std::ceil((y1 - o.y) * s.y)),
                   px(std::ceil((x1 - o.x) * s.x)), px(height - std::floor((y0 - o.y) * s.y))}
      .grown(1)
      .clipped(width, height);
}

bool touches(const PixelRect& r, const std::vector<PixelRect>& rects) {
  for (const PixelRect& o : rects)
    if (r.intersects(o)) return true;
  return false;
}

}  // namespace

RedrawPlan PanelRedraws::plan(const ImDrawData& data, const PixelRect& sceneChanged, int width,
                              int height, bool full) {
  const int n = data.CmdListsCount;
  std::vector<Drawn> now(n);
  for (int i = 0; i < n; ++i) {
    const ImDrawList& list = *data.CmdLists[i];
    now[i] = Drawn{&list, contentHash(list), listRect(list, data, width, height)};
  }
  RedrawPlan plan;
  if (full) {
    plan.restore.push_back(PixelRect{0, 0, width, height});
    for (int i = 0; i < n; ++i) plan.lists.push_back(i);
    last_ = std::move(now);
    return plan;
  }
  std::vector<PixelRect>& restore = plan.restore;
  if (!sceneChanged.empty()) restore.push_back(sceneChanged);
  std::vector<bool> redraw(n, false);
  // Lists that changed (or are new) are drawn again, over the scene restored where they are and
  // where they were; lists that are gone leave the scene where they were.
  for (int i = 0; i < n; ++i) {
    const auto before = std::find_if(last_.begin(), last_.end(),
                                     [&](const Drawn& d) { return d.list == now[i].list; });
    if (before != last_.end() && before->hash == now[i].hash && before->rect == now[i].rect)
      continue;
    redraw[i] = true;
    restore.push_back(now[i].rect);
    if (before != last_.end()) restore.push_back(before->rect);
  }
  for (const Drawn& d : last_) {
    const bool gone =
        std::none_of(now.begin(), now.end(), [&](const Drawn& x) { return x.list == d.list; });
    if (gone) restore.push_back(d.rect);
  }
  // Whatever overlaps a restored part is drawn again, and restored first itself: until nothing
  // more is drawn.
  for (bool more = true; more;) {
    more = false;
    for (int i = 0; i < n; ++i) {
      if (redraw[i] || !touches(now[i].rect, restore)) continue;
      redraw[i] = true;
      restore.push_back(now[i].rect);
      more = true;
    }
  }
  std::erase_if(restore, [](const PixelRect& r) { return r.empty(); });
  for (int i = 0; i < n; ++i)
    if (redraw[i]) plan.lists.push_back(i);
  last_ = std::move(now);
  return plan;
}

DrawDataSubset::DrawDataSubset(const ImDrawData& data, const std::vector<int>& lists)
    : data_(new ImDrawData(data)) {
  for (const int i : lists) lists_.push_back(data.CmdLists[i]);
  data_->CmdLists = lists_.data();
  data_->CmdListsCount = static_cast<int>(lists_.size());
  data_->TotalVtxCount = data_->TotalIdxCount = 0;
  for (const ImDrawList* l : lists_) {
    data_->TotalVtxCount += l->VtxBuffer.Size;
    data_->TotalIdxCount += l->IdxBuffer.Size;
  }
}

DrawDataSubset::~DrawDataSubset() {
  delete data_;
}

}  // namespace galsculpt
