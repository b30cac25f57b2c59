// PNG: signature, IHDR (size, 8-bit RGB), one IDAT holding the zlib stream of the rows (each led by filter type
// 0), IEND; every chunk with its CRC-32 (zlib's).
#include <zlib.h>

#include <fstream>

#include "rosmill/error.hpp"
#include "rosmill/verify/rgb_image.hpp"

namespace rosmill::core::verify {
namespace {

void put32(std::string& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(v >> shift & 0xff));
}

void chunk(std::string& out, const char type[4], const std::string& data) {
  put32(out, static_cast<uint32_t>(data.size()));
  const size_t start = out.size();
  out.append(type, 4);
  out += data;
  const auto* bytes = reinterpret_cast<const Bytef*>(out.data() + start);
  put32(out, static_cast<uint32_t>(crc32(crc32(0, nullptr, 0), bytes, static_cast<uInt>(out.size() - start))));
}

}  // namespace

void write_png(const std::string& path, const RgbImage& image) {
  std::string header;
  put32(header, static_cast<uint32_t>(image.width));
  put32(header, static_cast<uint32_t>(image.height));
  header += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, adaptive filtering, no interlace
  const size_t row = static_cast<size_t>(image.width) * 3;
  std::string raw;
  raw.reserve((row + 1) * image.height);
  for (int y = 0; y < image.height; ++y) {
    raw.push_back('\0');
    raw.append(reinterpret_cast<const char*>(image.pixels.data() + y * row), row);
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size, reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 6) != Z_OK)
    throw Error(path, "cannot compress the image");
  packed.resize(packed_size);
  std::string out("\x89PNG\r\n\x1a\n", 8);
  chunk(out, "IHDR", header);
  chunk(out, "IDAT", packed);
  chunk(out, "IEND", "");
  std::ofstream file(path, std::ios::binary);
  file.write(out.data(), static_cast<std::streamsize>(out.size()));
  if (!file) throw Error(path, "cannot write the image");
}

}  // namespace rosmill::core::verify
