// ExactWelder: one id per distinct position, in order of first appearance; -0 welds with +0; lookups that do
// not insert; growth far beyond the expected size.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rosmill/geometry/vertex_welder.hpp"

namespace rosmill::core {
namespace {

FloatWelder::Key float_key(float x, float y, float z) { return {weld_word(x), weld_word(y), weld_word(z)}; }

TEST(VertexWelder, IdsFollowFirstAppearanceAndZerosWeld) {
  FloatWelder welder(4);
  const std::vector<FloatWelder::Key> keys = {float_key(1, 2, 3), float_key(0.0f, 1, 0), float_key(1, 2, 3),
                                              float_key(-0.0f, 1, -0.0f), float_key(1, 2, 3.0000002f)};
  std::vector<uint32_t> ids(keys.size());
  welder.add_many(keys.data(), keys.size(), ids.data());
  EXPECT_EQ(ids, (std::vector<uint32_t>{0, 1, 0, 1, 2}));  // the next float after 3 is a new vertex
  ASSERT_EQ(welder.size(), 3u);
  EXPECT_EQ(key_position(welder.keys()[1]), Vec3(0, 1, 0));
  EXPECT_FALSE(std::signbit(key_position(welder.keys()[1]).x()));  // stored as +0
  EXPECT_EQ(key_position(welder.keys()[2]).z(), double(3.0000002f));
}

TEST(VertexWelder, DoubleKeysWeldExactlyAndFoldZeros) {
  DoubleWelder welder;
  const double next = std::nextafter(0.1, 1.0);  // the next double: a distinct position
  const std::vector<DoubleWelder::Key> keys = {weld_key(Vec3(0.1, -0.0, 5)), weld_key(Vec3(0.1, 0.0, 5)),
                                               weld_key(Vec3(next, 0, 5)), weld_key(Vec3(0.1, 0, -0.0 + 5))};
  std::vector<uint32_t> ids(keys.size());
  welder.add_many(keys.data(), keys.size(), ids.data());
  EXPECT_EQ(ids, (std::vector<uint32_t>{0, 0, 1, 0}));
}

TEST(VertexWelder, FindManyReadsWithoutInserting) {
  FloatWelder welder;
  const std::vector<FloatWelder::Key> present = {float_key(1, 0, 0), float_key(0, 1, 0)};
  std::vector<uint32_t> ids(2);
  // Before its first key a welder has no table yet: nothing is found.
  welder.find_many(present.data(), present.size(), ids.data());
  EXPECT_EQ(ids, (std::vector<uint32_t>{FloatWelder::kAbsent, FloatWelder::kAbsent}));
  welder.add_many(present.data(), present.size(), ids.data());
  const std::vector<FloatWelder::Key> asked = {float_key(0, 1, 0), float_key(0, 0, 1), float_key(-0.0f, 1, 0)};
  std::vector<uint32_t> found(asked.size());
  welder.find_many(asked.data(), asked.size(), found.data());
  EXPECT_EQ(found, (std::vector<uint32_t>{1, FloatWelder::kAbsent, 1}));
  EXPECT_EQ(welder.size(), 2u);
  // Its table released, the keys stay.
  welder.release_table();
  ASSERT_EQ(welder.size(), 2u);
  EXPECT_EQ(welder.keys()[0], present[0]);
  EXPECT_EQ(welder.keys()[1], present[1]);
}

TEST(VertexWelder, GrowsFarBeyondItsExpectedSize) {
  // 200,000 distinct random positions, each added twice, into a welder expecting 10: every id survives the
  // table's growth, and a second pass finds the same ids.
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-100.0f, 100.0f);
  std::vector<FloatWelder::Key> keys(200000);
  for (auto& k : keys) k = float_key(coordinate(random), coordinate(random), coordinate(random));
  FloatWelder welder(10);
  std::vector<uint32_t> first(keys.size()), again(keys.size()), found(keys.size());
  welder.add_many(keys.data(), keys.size(), first.data());
  welder.add_many(keys.data(), keys.size(), again.data());
  welder.find_many(keys.data(), keys.size(), found.data());
  ASSERT_EQ(welder.size(), keys.size());  // random floats in this range do not repeat at this count (seeded)
  for (size_t i = 0; i < keys.size(); ++i) {
    ASSERT_EQ(first[i], uint32_t(i));
    ASSERT_EQ(again[i], uint32_t(i));
    ASSERT_EQ(found[i], uint32_t(i));
  }
}

}  // namespace
}  // namespace rosmill::core
