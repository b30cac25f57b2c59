#include "cloud_format.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "rosmill/error.hpp"
#include "rosmill/io/cloud_io.hpp"

namespace rosmill::core {
namespace {

std::string lower_extension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// "pcd" or "ply" from the file's first bytes; empty when they are neither.
std::string format_by_content(const std::string& path) {
  char head[16] = {};
  // Only a regular file is opened here (a FIFO would block the open): anything else is refused by the reader.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return "";
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  const std::string start(head, static_cast<size_t>(in.gcount()));
  if (start.rfind("ply\n", 0) == 0 || start.rfind("ply\r\n", 0) == 0) return "ply";
  if (start.rfind("# .PCD", 0) == 0 || start.rfind("VERSION", 0) == 0 || start.rfind("FIELDS", 0) == 0)
    return "pcd";
  return "";
}

}  // namespace

namespace io {

std::string cloud_format(const std::string& path) {
  const std::string by_content = format_by_content(path);
  if (!by_content.empty()) return by_content;
  const std::string ext = lower_extension(path);
  if (ext == "pcd" || ext == "ply") return ext;
  throw Error(path, "not a point cloud file: neither PCD nor PLY (by content and extension)");
}

}  // namespace io

bool is_cloud_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == "pcd" || ext == "ply";
}

bool is_cloud_file(const std::string& path) { return is_cloud_path(path) || !format_by_content(path).empty(); }

}  // namespace rosmill::core
