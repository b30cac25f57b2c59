// Layout checks of point cloud files against their real size, run before PCL reads them (PCL trusts headers).
// Internal to src/io.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace rosmill::core::io {

// Throw Error naming `path` when the header is malformed or the body is shorter than the header says.
void check_pcd_layout(const char* data, size_t size, const std::string& path);
void check_ply_layout(const char* data, size_t size, const std::string& path);

}  // namespace rosmill::core::io
