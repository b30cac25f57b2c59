// The paths a job file names, read through the package's YAML fields (rosmill/yaml/fields.hpp: errors name the
// file, the line and the field). Private to the job area.
#pragma once
#include <filesystem>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/yaml/fields.hpp"

namespace rosmill::core::job {

using yaml::Fields;

// A path the job names, relative to the job file's folder (a primitive and an empty path as they are).
inline std::string resolve(const std::string& path, const std::string& folder) {
  if (path.rfind("primitive:", 0) == 0 || path.empty()) return path;
  const std::filesystem::path p(path);
  return p.is_absolute() ? path : (std::filesystem::path(folder) / p).lexically_normal().string();
}

// Whether a named file exists; a name the system cannot look up (too long, a loop of links) is refused at `where`.
inline bool file_exists(const std::string& path, const std::string& where) {
  std::error_code failure;
  const bool exists = std::filesystem::exists(path, failure);
  if (failure) throw Error(where, "cannot look up " + path + ": " + failure.message());
  return exists;
}
}  // namespace rosmill::core::job
