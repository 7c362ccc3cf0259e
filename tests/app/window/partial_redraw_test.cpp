#include "app/window/partial_redraw.h"

#include <gtest/gtest.h>
#include <imgui.h>

#include <algorithm>
#include <memory>

namespace galsculpt {
namespace {

constexpr int kWidth = 400, kHeight = 300;

// A panel: one quad of ImGui's (rows from the top) at [x0, x1) x [y0, y1), with a colour that
// stands for its content.
std::unique_ptr<ImDrawList> panel(float x0, float y0, float x1, float y1, ImU32 colour) {
  auto list = std::make_unique<ImDrawList>(nullptr);
  for (const ImVec2 p : {ImVec2(x0, y0), ImVec2(x1, y0), ImVec2(x1, y1), ImVec2(x0, y1)})
    list->VtxBuffer.push_back(ImDrawVert{p, ImVec2(0, 0), colour});
  for (const ImDrawIdx i : {0, 1, 2, 0, 2, 3}) list->IdxBuffer.push_back(i);
  ImDrawCmd cmd;
  cmd.ClipRect = ImVec4(0, 0, kWidth, kHeight);
  cmd.ElemCount = 6;
  list->CmdBuffer.push_back(cmd);
  return list;
}

struct Frame {
  std::vector<ImDrawList*> lists;
  ImDrawData data;
  explicit Frame(std::vector<ImDrawList*> l) : lists(std::move(l)) {
    data.Valid = true;
    data.CmdLists = lists.data();
    data.CmdListsCount = static_cast<int>(lists.size());
    data.DisplayPos = ImVec2(0, 0);
    data.DisplaySize = ImVec2(kWidth, kHeight);
    data.FramebufferScale = ImVec2(1, 1);
  }
};

bool covers(const std::vector<PixelRect>& rects, const PixelRect& r) {
  return std::any_of(rects.begin(), rects.end(), [&](const PixelRect& o) {
    return o.x0 <= r.x0 && o.y0 <= r.y0 && o.x1 >= r.x1 && o.y1 >= r.y1;
  });
}

TEST(PanelRedraws, OnlyWhatChangedOrLiesUnderAChangeIsDrawnAgain) {
  // Left panel, a tooltip over its right edge, a panel on the right; GL rows from the bottom.
  auto left = panel(0, 0, 100, 200, 0xff000001), tip = panel(90, 50, 150, 80, 0xff000002),
       right = panel(300, 0, 400, 100, 0xff000003);
  const PixelRect leftRect{0, 99, 100, 300};  // rows 0..200 from the top, grown by a pixel
  PanelRedraws redraws;
  Frame first({left.get(), tip.get(), right.get()});
  RedrawPlan p = redraws.plan(first.data, {}, kWidth, kHeight, true);
  EXPECT_EQ(p.lists, (std::vector<int>{0, 1, 2})) << "the first draw: everything";
  EXPECT_TRUE(covers(p.restore, PixelRect{0, 0, kWidth, kHeight}));

  p = redraws.plan(first.data, {}, kWidth, kHeight, false);
  EXPECT_TRUE(p.lists.empty() && p.restore.empty()) << "nothing changed: nothing drawn";

  // The right panel's content changes: it alone is drawn again, over the scene restored.
  right->VtxBuffer[0].col = 0xff000004;
  p = redraws.plan(first.data, {}, kWidth, kHeight, false);
  EXPECT_EQ(p.lists, (std::vector<int>{2}));
  EXPECT_TRUE(covers(p.restore, PixelRect{300, 200, 400, 300}));

  // The tooltip changes: the left panel under it is drawn again too, first.
  tip->VtxBuffer[0].col = 0xff000005;
  p = redraws.plan(first.data, {}, kWidth, kHeight, false);
  EXPECT_EQ(p.lists, (std::vector<int>{0, 1}));
  EXPECT_TRUE(covers(p.restore, leftRect));

  // The scene changes under the right panel only.
  p = redraws.plan(first.data, PixelRect{350, 250, 360, 260}, kWidth, kHeight, false);
  EXPECT_EQ(p.lists, (std::vector<int>{2}));
  EXPECT_TRUE(covers(p.restore, PixelRect{350, 250, 360, 260}));

  // The scene changes clear of every panel: the scene's part is restored, no panel drawn.
  p = redraws.plan(first.data, PixelRect{200, 10, 250, 40}, kWidth, kHeight, false);
  EXPECT_TRUE(p.lists.empty());
  EXPECT_EQ(p.restore, (std::vector<PixelRect>{{200, 10, 250, 40}}));

  // The tooltip moves away and then is gone: where it was is restored each time.
  for (ImDrawVert& v : tip->VtxBuffer) v.pos.y += 180;  // rows 230..260 from the top
  p = redraws.plan(first.data, {}, kWidth, kHeight, false);
  EXPECT_TRUE(covers(p.restore, PixelRect{89, 219, 151, 251})) << "where it was";
  EXPECT_TRUE(covers(p.restore, PixelRect{89, 39, 151, 71})) << "where it is";
  Frame without({left.get(), right.get()});
  p = redraws.plan(without.data, {}, kWidth, kHeight, false);
  EXPECT_TRUE(covers(p.restore, PixelRect{89, 39, 151, 71})) << "gone: the scene shows again";
  EXPECT_TRUE(p.lists.empty()) << "nothing left under where it was";
}

TEST(PanelRedraws, ASubsetDrawsOnlyTheChosenLists) {
  auto a = panel(0, 0, 10, 10, 0xff0000ff), b = panel(20, 20, 40, 40, 0xff00ff00);
  Frame frame({a.get(), b.get()});
  DrawDataSubset subset(frame.data, {1});
  ASSERT_EQ(subset.get()->CmdListsCount, 1);
  EXPECT_EQ(subset.get()->CmdLists[0], b.get());
  EXPECT_EQ(subset.get()->TotalVtxCount, 4);
  EXPECT_EQ(subset.get()->TotalIdxCount, 6);
}

}  // namespace
}  // namespace galsculpt
