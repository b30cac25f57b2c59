// The tool table (config/tools.yaml): every tool's cutter and how to run it, validated when read.
#pragma once
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

// Reads and validates a table; every error names the file, the tool (id or position) and the field.
ToolTable read_tool_table(const std::string& path);
// The same from YAML text; `name` stands for the file in messages.
ToolTable parse_tool_table(const std::string& yaml_text, const std::string& name);

// A tool with the defaults of a bare cutter spec (no table): feeds by diameter, stepover 10 % (ball, bull) or
// 40 % (flat) of the diameter, step-down half the diameter.
Tool default_tool(const Cutter& cutter);
// "--tool" as a number (an id in `table`, which must then be given) or a cutter spec (ball:D, flat:D, bull:D:r).
Tool resolve_tool(const std::string& spec, const ToolTable* table);

}  // namespace rosmill::core
