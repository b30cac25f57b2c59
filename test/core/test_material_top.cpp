// The material grid planning reads (plan/material_top.hpp): growing it keeps every cell where it was.
#include <gtest/gtest.h>

#include <cmath>

#include "rosmill/plan/material_top.hpp"

using namespace rosmill::core;

TEST(MaterialTop, PaddingKeepsEveryCellInPlaceAndAddsNothingAround) {
  MaterialTop m;
  m.x0 = 10, m.y0 = -5, m.cell = 0.5, m.nx = 3, m.ny = 2;
  m.top = {1, 2, 3, 4, 5, 6};
  m.cut = {1, -INFINITY, 3, 4, -INFINITY, 6};
  m.fixture = {-INFINITY, -INFINITY, 7, -INFINITY, -INFINITY, -INFINITY};
  m.keep = {1, 0, 1, 0, 1, 0};
  m.keep_low = {0, NAN, 0, NAN, 0, NAN};
  m.keep_high = {1, NAN, 1, NAN, 1, NAN};
  const MaterialTop before = m;
  m.pad(2);
  ASSERT_NO_THROW(m.check("padded"));
  EXPECT_EQ(m.nx, 7);
  EXPECT_EQ(m.ny, 6);
  EXPECT_DOUBLE_EQ(m.x0, 9.0);
  EXPECT_DOUBLE_EQ(m.y0, -6.0);
  for (int j = 0; j < m.ny; ++j)
    for (int i = 0; i < m.nx; ++i) {
      const size_t c = size_t(j) * m.nx + i;
      const int bi = i - 2, bj = j - 2;
      if (bi >= 0 && bi < before.nx && bj >= 0 && bj < before.ny) {
        const size_t b = size_t(bj) * before.nx + bi;
        EXPECT_EQ(m.top[c], before.top[b]);
        EXPECT_EQ(m.cut[c], before.cut[b]);
        EXPECT_EQ(m.fixture[c], before.fixture[b]);
        EXPECT_EQ(m.keep[c], before.keep[b]);
        EXPECT_EQ(std::isnan(m.keep_low[c]), std::isnan(before.keep_low[b]));
      } else {
        EXPECT_EQ(m.top[c], -INFINITY);
        EXPECT_EQ(m.cut[c], -INFINITY);
        EXPECT_EQ(m.fixture[c], -INFINITY);
        EXPECT_EQ(m.keep[c], 0);
      }
    }
  // The same questions get the same answers: the highest under a point of the old grid, and nothing beside it.
  EXPECT_EQ(m.highest(), before.highest());
  EXPECT_EQ(m.highest_under(Vec2(11.25, -4.25), 0.1), before.highest_under(Vec2(11.25, -4.25), 0.1));
  EXPECT_EQ(m.highest_under(Vec2(9.25, -5.75), 0.1), -INFINITY);
}
