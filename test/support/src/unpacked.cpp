#include "rosmill/testing/unpacked.hpp"

#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "rosmill/error.hpp"

namespace rosmill::core {

std::string unpacked(const std::string& gz, const std::string& dir) {
  const std::filesystem::path out = std::filesystem::path(dir) / std::filesystem::path(gz).stem();
  gzFile in = gzopen(gz.c_str(), "rb");
  if (!in) throw Error(gz, "cannot open");
  std::ofstream o(out, std::ios::binary);
  std::vector<char> buf(1 << 20);
  int n;
  while ((n = gzread(in, buf.data(), unsigned(buf.size()))) > 0) o.write(buf.data(), n);
  gzclose(in);
  return out.string();
}

}  // namespace rosmill::core
