// Pixel rectangles (app/render/pixel_rect.h): half-open, empty ones add nothing, clipping and
// growing as the partial redraws plan with them.
#include "app/render/pixel_rect.h"

#include <gtest/gtest.h>

namespace galsculpt {
namespace {

TEST(PixelRect, HalfOpenAreasIntersectionsAndUnions) {
  const PixelRect a{0, 0, 10, 5}, b{10, 0, 20, 5}, c{5, 2, 15, 8};
  EXPECT_EQ(a.area(), 50);
  EXPECT_FALSE(a.intersects(b)) << "they share an edge, not a pixel";
  EXPECT_TRUE(a.intersects(c));
  EXPECT_EQ(a.united(b), (PixelRect{0, 0, 20, 5}));
  const PixelRect none{};
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.area(), 0);
  EXPECT_EQ(none.united(c), c);
  EXPECT_EQ(c.united(none), c);
  EXPECT_FALSE(none.intersects(a));
  EXPECT_TRUE((PixelRect{4, 4, 4, 9}).empty()) << "no width";
}

TEST(PixelRect, ClippedToTheFramebufferAndGrown) {
  EXPECT_EQ((PixelRect{-5, -5, 30, 30}).clipped(20, 10), (PixelRect{0, 0, 20, 10}));
  EXPECT_EQ((PixelRect{25, 0, 30, 5}).clipped(20, 10), PixelRect{}) << "off the screen";
  EXPECT_EQ((PixelRect{5, 5, 6, 6}).grown(2), (PixelRect{3, 3, 8, 8}));
  EXPECT_EQ(PixelRect{}.grown(2), PixelRect{}) << "nothing grows from nothing";
}

}  // namespace
}  // namespace galsculpt
