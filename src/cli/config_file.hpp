// Where a command finds a configuration file it was not given (config/tools.yaml, config/machine.yaml): the
// working folder's config/NAME when there is one (a cell keeps its own tools and machine next to its parts), else
// the package's own config folder, so that the commands run from any folder.
#pragma once
#include <filesystem>
#include <string>

namespace rosmill::cli {

inline std::string default_config(const std::string& name) {
  const std::string local = "config/" + name;
  if (std::filesystem::exists(local)) return local;
  return std::string(ROSMILL_PACKAGE_CONFIG) + "/" + name;
}

}  // namespace rosmill::cli
