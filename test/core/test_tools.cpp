// Tool table: the shipped config/tools.yaml reads, and every kind of bad entry is refused with a message that
// names the file, the line and the field.
#include <gtest/gtest.h>

#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "error_of.hpp"

using namespace rosmill::core;

namespace {

std::string table_error(const std::string& yaml) {
  try {
    parse_tool_table(yaml, "t.yaml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kGood =
    "tools:\n"
    "  - {id: 7, name: bull, type: bull, diameter: 8, corner_radius: 1, flute_length: 25, shank_diameter: 8,\n"
    "     spindle_rpm: 12000, feed: 1400, plunge_feed: 350, stepover: 2, stepdown: 1.5}\n";

std::string with(const std::string& from, const std::string& to) {
  std::string s = kGood;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

}  // namespace

TEST(ToolTable, ShippedTableReads) {
  const ToolTable t = read_tool_table(ROSMILL_SOURCE_DIR "/config/tools.yaml");
  ASSERT_GE(t.tools.size(), 4u);
  const Tool& ball = t.get(2);
  EXPECT_EQ(ball.cutter.type, CutterType::BallEnd);
  EXPECT_DOUBLE_EQ(ball.cutter.diameter, 6.0);
  EXPECT_DOUBLE_EQ(ball.cutter.corner_radius, 3.0);
  EXPECT_GT(ball.feed, ball.plunge_feed);
  EXPECT_EQ(t.get(4).cutter.type, CutterType::BullNose);
  EXPECT_DOUBLE_EQ(t.get(4).cutter.corner_radius, 1.0);
  EXPECT_THROW(t.get(99), Error);
}

TEST(ToolTable, GoodEntryFields) {
  const ToolTable t = parse_tool_table(kGood, "t.yaml");
  const Tool& b = t.get(7);
  EXPECT_EQ(b.name, "bull");
  EXPECT_DOUBLE_EQ(b.cutter.flute_length, 25);
  EXPECT_DOUBLE_EQ(b.spindle_rpm, 12000);
  EXPECT_DOUBLE_EQ(b.stepover, 2);
  EXPECT_DOUBLE_EQ(b.stepdown, 1.5);
}

TEST(ToolTable, ErrorsNameFileLineAndField) {
  EXPECT_EQ(table_error(with("diameter: 8", "diameter: -8")),
            "t.yaml:2 tools[0].diameter: must be greater than 0, got -8");
  EXPECT_EQ(table_error(with("feed: 1400", "feed: fast")), "t.yaml:3 tools[0].feed: expected a number, got 'fast'");
  EXPECT_EQ(table_error(with("type: bull", "type: drill")),
            "t.yaml:2 tools[0].type: must be flat, ball or bull, got 'drill'");
  EXPECT_EQ(table_error(with("corner_radius: 1", "corner_radius: 5")),
            "t.yaml:2 tools[0].corner_radius: is larger than half the diameter");
  EXPECT_EQ(table_error(with(", stepdown: 1.5", "")), "t.yaml:2 tools[0].stepdown: missing (required)");
  EXPECT_EQ(table_error(with("stepover: 2", "stepover: 20")),
            "t.yaml:3 tools[0].stepover: is larger than the diameter");
  EXPECT_EQ(table_error(with("name: bull", "nmae: bull"))
                .rfind("t.yaml:2 tools[0].nmae: unknown field (expected one of corner_radius, diameter, feed,", 0),
            0u);
  EXPECT_EQ(table_error(with("id: 7", "id: 2.5")),
            "t.yaml:2 tools[0].id: must be a whole number in [1, 99999], got 2.5");
  EXPECT_EQ(table_error(std::string(kGood) + std::string(kGood).substr(7)),
            "t.yaml:4 tools[1].id: tool 7 is listed twice (first at line 2)");
  EXPECT_EQ(table_error("tools: []"), "t.yaml:1 tools: expected a non-empty list of tools");
  EXPECT_EQ(table_error("tool: []").rfind("t.yaml:1 tool: unknown field (expected one of tools)", 0), 0u);
  EXPECT_NE(table_error("tools: [ {id: 1").find("t.yaml:1: not valid YAML"), std::string::npos);
  EXPECT_EQ(table_error(with("type: bull, diameter: 8, corner_radius: 1", "type: ball, diameter: 8, corner_radius: 1")),
            "t.yaml:2 tools[0].corner_radius: must be half the diameter for a ball end mill");
}

TEST(ToolTable, ResolveSpecOrId) {
  const ToolTable t = parse_tool_table(kGood, "t.yaml");
  EXPECT_EQ(resolve_tool("7", &t).id, 7);
  EXPECT_THROW(resolve_tool("7", nullptr), Error);
  const Tool b = resolve_tool("ball:6", nullptr);
  EXPECT_EQ(b.cutter.type, CutterType::BallEnd);
  EXPECT_DOUBLE_EQ(b.stepover, 0.6);
  EXPECT_THROW(resolve_tool("ball:x", &t), Error);
  EXPECT_THROW(read_tool_table("/nonexistent/tools.yaml"), Error);
}

// An inline tool carries its number in the controller's tool table after '@'; without one it has none (T0 on
// LinuxCNC would empty the spindle), and the spec it reads back from names the same tool.
TEST(ToolTable, InlineToolsCarryTheirNumber) {
  EXPECT_EQ(resolve_tool("ball:6", nullptr).id, kNoToolNumber);
  const Tool f = resolve_tool("flat:4@7", nullptr);
  EXPECT_EQ(f.id, 7);
  EXPECT_EQ(f.cutter.type, CutterType::FlatEnd);
  EXPECT_DOUBLE_EQ(f.cutter.diameter, 4.0);
  const Tool b = resolve_tool("bull:8:1.5@12", nullptr);
  EXPECT_EQ(b.id, 12);
  EXPECT_DOUBLE_EQ(b.cutter.corner_radius, 1.5);
  EXPECT_EQ(inline_tool_spec(b.cutter, b.id), "bull:8:1.5@12");
  EXPECT_EQ(inline_tool_spec(Cutter::ball(0.1), kNoToolNumber), "ball:0.1");
  const Tool back = resolve_tool(inline_tool_spec(Cutter::flat(6.35), 3), nullptr);
  EXPECT_EQ(back.id, 3);
  EXPECT_EQ(back.cutter.diameter, 6.35);
  EXPECT_EQ(error_of([] { resolve_tool("flat:4@0", nullptr); }),
            "--tool: tool number '0' must be a whole number in [1, 99999]: the tool's pocket in the controller's "
            "tool table");
  EXPECT_THROW(resolve_tool("flat:4@", nullptr), Error);
  EXPECT_THROW(resolve_tool("flat:4@x", nullptr), Error);
  EXPECT_THROW(resolve_tool("flat:4@100000", nullptr), Error);
  EXPECT_THROW(resolve_tool("flat:4@7@8", nullptr), Error);
  EXPECT_THROW(resolve_tool("@7", nullptr), Error);
}
