// The input policy (rosmill/input_file.hpp) under hostile paths: a device, a FIFO, a file beyond the size limit
// and a gzip bomb are refused by every reader with the reason, in bounded time and memory, and `rosmill info
// /dev/zero` says why and exits 1.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <zlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "error_of.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/machine_limits.hpp"
#include "rosmill/gcode/post.hpp"
#include "rosmill/input_file.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/planner/presets.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"
#include "rosmill/verify/gcode_reader.hpp"

using namespace rosmill::core;
namespace fs = std::filesystem;

namespace {

// Every reader of a file, by name.
const std::vector<std::pair<std::string, std::function<void(const std::string&)>>>& readers() {
  static const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> list = {
      {"stl", [](const std::string& p) { read_stl(p); }},
      {"cloud", [](const std::string& p) { read_cloud(p); }},
      {"tool table", [](const std::string& p) { read_tool_table(p); }},
      {"presets", [](const std::string& p) { read_presets(p); }},
      {"toolpath", [](const std::string& p) { read_toolpath_file(p); }},
      {"machine", [](const std::string& p) { gcode::load_machine_limits(p); }},
      {"program lines", [](const std::string& p) { gcode::read_program_lines(p); }},
      {"G-code", [](const std::string& p) { verify::read_gcode(p, verify::ToolSetup{}); }},
  };
  return list;
}

long max_rss_kib() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

// A gzip member of `mib` MiB of zeros (deflate compresses them about a thousand to one).
std::string gzip_zeros(size_t mib) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY), Z_OK);
  std::vector<char> zeros(1 << 20, 0);
  std::string out;
  char buf[1 << 16];
  for (size_t k = 0; k <= mib; ++k) {
    zs.next_in = reinterpret_cast<Bytef*>(zeros.data());
    zs.avail_in = k < mib ? uInt(zeros.size()) : 0;
    const int flush = k < mib ? Z_NO_FLUSH : Z_FINISH;
    do {
      zs.next_out = reinterpret_cast<Bytef*>(buf);
      zs.avail_out = sizeof buf;
      deflate(&zs, flush);
      out.append(buf, sizeof buf - zs.avail_out);
    } while (zs.avail_out == 0);
  }
  deflateEnd(&zs);
  return out;
}

class HostileFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("rosmill_hostile_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST_F(HostileFiles, EveryReaderRefusesADeviceUpFront) {
  for (const auto& reader : readers()) {  // not a structured binding: C++17 lambdas cannot capture one
    const std::string& name = reader.first;
    const auto& read = reader.second;
    const auto t0 = std::chrono::steady_clock::now();
    const std::string e = error_of([&] { read("/dev/zero"); });
    EXPECT_NE(e.find("/dev/zero: is a character device, not a regular file"), std::string::npos) << name << ": " << e;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0) << name;
  }
}

TEST_F(HostileFiles, EveryReaderRefusesAFifoWithoutWaitingForAWriter) {
  const std::string fifo = (dir_ / "part.stl").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const auto& reader : readers()) {  // not a structured binding: C++17 lambdas cannot capture one
    const std::string& name = reader.first;
    const auto& read = reader.second;
    const std::string e = error_of([&] { read(fifo); });
    EXPECT_NE(e.find("is a FIFO (named pipe), not a regular file"), std::string::npos) << name << ": " << e;
  }
}

TEST_F(HostileFiles, EveryReaderRefusesAnEmptyFileAndADirectory) {
  const std::string empty = (dir_ / "empty.yaml").string();
  std::ofstream(empty).close();
  for (const auto& reader : readers()) {  // not a structured binding: C++17 lambdas cannot capture one
    const std::string& name = reader.first;
    const auto& read = reader.second;
    EXPECT_NE(error_of([&] { read(empty); }).find("empty file"), std::string::npos) << name;
    EXPECT_NE(error_of([&] { read(dir_.string()); }).find("is a directory"), std::string::npos) << name;
  }
}

TEST_F(HostileFiles, EveryReaderRefusesAFileBeyondTheLimitWithoutReadingIt) {
  // Sparse: a gigabyte and a byte that takes no disk.
  const std::string big = (dir_ / "big.stl").string();
  std::ofstream(big).close();
  fs::resize_file(big, kMaxInputBytes + 1);
  for (const auto& reader : readers()) {  // not a structured binding: C++17 lambdas cannot capture one
    const std::string& name = reader.first;
    const auto& read = reader.second;
    const auto t0 = std::chrono::steady_clock::now();
    const std::string e = error_of([&] { read(big); });
    EXPECT_NE(e.find("big.stl: file of 1073741825 bytes is larger than the 1073741824 bytes (1024 MiB) rosmill reads"),
              std::string::npos)
        << name << ": " << e;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0) << name;
  }
}

TEST_F(HostileFiles, AGzipBombIsRefusedBeforeItsSizeIsAllocated) {
  // 32 members of 64 MiB of zeros: 2 GiB inflated from about 2 MB, twice the most rosmill reads.
  const std::string member = gzip_zeros(64);
  const std::string bomb = (dir_ / "bomb.stl.gz").string();
  {
    std::ofstream out(bomb, std::ios::binary);
    for (int k = 0; k < 32; ++k) out << member;
  }
  ASSERT_LT(fs::file_size(bomb), 4u << 20);
  const long rss0 = max_rss_kib();
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = error_of([&] { read_stl(bomb); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_NE(e.find("bomb.stl.gz: gzip stream inflates to more than 1024 MiB"), std::string::npos) << e;
  EXPECT_LT(max_rss_kib() - rss0, 64 * 1024) << "KiB held while refusing the bomb";
  EXPECT_LT(seconds, 20.0);
}

TEST_F(HostileFiles, ASmallGzippedStlStillReads) {
  const std::string plain = (dir_ / "cube.stl").string(), packed = plain + ".gz";
  ASSERT_EQ(run_rosmill_shell("primitive cube -o " + plain + " >/dev/null 2>&1").status, 0);
  ASSERT_EQ(std::system(("gzip -k " + plain).c_str()), 0);
  EXPECT_EQ(read_stl(packed).face_count(), 12u);
}

TEST_F(HostileFiles, InfoOnDevZeroSaysWhyAndExitsNonZero) {
  const CliRun run = run_rosmill_shell("info /dev/zero 2>&1");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.out.find("/dev/zero: is a character device, not a regular file"), std::string::npos) << run.out;
}
