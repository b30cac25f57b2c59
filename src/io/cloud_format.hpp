// Which point cloud format a file holds, by its first bytes or its extension: apart from the reader, so that a
// program that only tells clouds from meshes (the `rosmill` front's `info`) does not link PCL. Internal to src/io.
#pragma once
#include <string>

namespace rosmill::core::io {

// "pcd" or "ply" from the file's first bytes, falling back on the extension; throws Error naming the file when
// it is neither.
std::string cloud_format(const std::string& path);

}  // namespace rosmill::core::io
