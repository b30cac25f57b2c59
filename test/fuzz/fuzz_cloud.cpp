// PCD and PLY files: rosmill's layout checks run on the bytes before PCL reads them (PCL trusts headers), then the
// points are taken from PCL's blob by rosmill. The whole of read_cloud() runs on each input, as for a user's file:
// PCL reads only from a path, so the input is held in an anonymous memory file (memfd), not written to disk.
#include <sys/mman.h>
#include <unistd.h>

#include "fuzz_support.hpp"
#include "rosmill/io/cloud_io.hpp"

namespace {

// One memory file for the whole run, refilled for each input.
int memory_file() {
  static const int fd = memfd_create("rosmill-fuzz-cloud", 0);
  if (fd < 0) rosmill::fuzz::finding("memfd_create failed");
  return fd;
}

void refill(int fd, const uint8_t* data, size_t size) {
  if (ftruncate(fd, 0) != 0 || lseek(fd, 0, SEEK_SET) != 0) rosmill::fuzz::finding("cannot reset the memory file");
  for (size_t done = 0; done < size;) {
    const ssize_t n = write(fd, data + done, size - done);
    if (n <= 0) rosmill::fuzz::finding("cannot fill the memory file");
    done += size_t(n);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rosmill;
  const int fd = memory_file();
  refill(fd, data, size);
  const std::string path = "/proc/self/fd/" + std::to_string(fd);
  fuzz::read_or_refuse([&] {
    core::CloudInfo info;
    const core::PointCloud cloud = core::read_cloud(path, {}, &info);
    fuzz::require(!cloud.points.empty(), "a cloud without points was accepted");
    fuzz::require(cloud.points.size() + info.dropped_nonfinite == info.points_in_file,
                  "points read and dropped do not add up to the file's");
    for (const core::Vec3& p : cloud.points) fuzz::require(p.allFinite(), "a point that is not finite");
  });
  return 0;
}
