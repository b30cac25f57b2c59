// Toolpath files (toolpath.json): what `rosmill plan -o` writes and `rosmill post` / `rosmill verify` read.
//
// {"format":"rosmill-toolpath","version":1,"units":"mm","toolpaths":[T, ...]}   one T per tool, in order:
// T = {"strategy":s,"tool":{...},"safe_z":z,"clearance_z":z,"start":[x,y,z],
//      "passes":[{"name":n,"moves":[[x,y,z,type,feed],...]}]}                 type: 0 rapid, 1 feed, 2 plunge
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "rosmill/toolpath/toolpath.hpp"

namespace rosmill::core {

nlohmann::json toolpath_to_json(const Toolpath& tp);
// Throws Error naming `where` and the offending field on a malformed toolpath object.
Toolpath toolpath_from_json(const nlohmann::json& t, const std::string& where);

void write_toolpath_file(const std::string& path, const std::vector<Toolpath>& job);
std::vector<Toolpath> read_toolpath_file(const std::string& path);
// The same from the file's text; `path` stands for the file in messages.
std::vector<Toolpath> parse_toolpath_text(const std::string& text, const std::string& path);

nlohmann::json tool_to_json(const Tool& tool);
Tool tool_from_json(const nlohmann::json& j, const std::string& where);

}  // namespace rosmill::core
