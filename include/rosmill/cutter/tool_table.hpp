// The tool table (config/tools.yaml): every tool's cutter and how to run it, validated when read.
#pragma once
#include <set>
#include <string>
#include <vector>

#include "rosmill/cutter/cutter.hpp"

namespace rosmill::core {

struct ToolTable {
  std::string source;  // file name (for messages)
  std::vector<Tool> tools;

  // Throws Error naming the table and the id when no tool has it.
  const Tool& get(int id) const;
};

// Reads and validates a table; every error names the file, the line and the field ("tools.yaml:22 tools[4].feed").
ToolTable read_tool_table(const std::string& path);
// The same from YAML text; `name` stands for the file in messages. `other_fields`: the top-level fields besides
// `tools` that the file may hold (a presets file's presets and templates), any other is refused.
ToolTable parse_tool_table(const std::string& yaml_text, const std::string& name,
                           const std::set<std::string>& other_fields = {});

// A tool with the defaults of a bare cutter spec (no table): feeds by diameter, stepover 10 % (ball, bull) or
// 40 % (flat) of the diameter, step-down half the diameter. Its number (T word) is kNoToolNumber.
Tool default_tool(const Cutter& cutter);

// The number of a tool given only by its cutter: it plans, but no program is written with it (on LinuxCNC, T0 M6
// empties the spindle and G43 H0 applies no length offset).
constexpr int kNoToolNumber = 0;
// The largest tool number a table or a spec may give.
constexpr int kMaxToolNumber = 99999;

// A tool number as text ("7"): a whole number in [1, kMaxToolNumber]; throws Error naming `where` otherwise.
int parse_tool_number(const std::string& text, const std::string& where);

// "--tool" as a number (an id in `table`, which must then be given) or a cutter spec, with the tool's number in the
// controller's tool table after '@': ball:D@N, flat:D@N, bull:D:r@N. A spec without '@N' has kNoToolNumber.
Tool resolve_tool(const std::string& spec, const ToolTable* table, const std::string& where = "--tool");

// The spec resolve_tool reads back for an inline tool: "flat:4@7" (the numbers in their shortest exact form).
std::string inline_tool_spec(const Cutter& cutter, int number);

}  // namespace rosmill::core
