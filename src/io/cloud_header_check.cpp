// Header checks for PCD and PLY files before PCL reads them. PCL's readers trust their headers (a text file
// named .pcd crashes pcl::PCDReader), so the layout is checked here against the file's real size first.
#include "cloud_header_check.hpp"

#include <set>
#include <sstream>
#include <vector>

#include "rosmill/error.hpp"
#include "rosmill/text_words.hpp"

namespace rosmill::core::io {
namespace {

// The line that starts at `pos`, without its '\n'; `pos` moves past it.
std::string next_line(const char* data, size_t size, size_t& pos) {
  size_t end = pos;
  while (end < size && data[end] != '\n') ++end;
  std::string line(data + pos, end - pos);
  pos = end < size ? end + 1 : end;
  return line;
}

// Splits the header into lines up to and including the one whose first word is `last_key`; returns the offset of
// the first byte after it, or throws when the header never ends. A header line holds printable text, tabs and a
// closing carriage return only: PCL splits words at spaces, tabs and carriage returns but reads numbers across
// any white space, so a vertical tab or form feed would make the two readings of one line differ.
size_t header_lines(const char* data, size_t size, const std::string& last_key, const std::string& path,
                    std::vector<std::string>& lines) {
  size_t pos = 0;
  while (pos < size) {
    std::string line = next_line(data, size, pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (const char c : line)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
        throw Error(path, "malformed header: line " + std::to_string(lines.size() + 1) +
                              " holds a control character (byte " + std::to_string(int(static_cast<unsigned char>(c))) +
                              ")");
    lines.push_back(line);
    if (first_word(line) == last_key) return pos;
    if (lines.size() > 10000) break;
  }
  throw Error(path, "malformed header: no '" + last_key + "' line");
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

uint64_t to_count(const std::string& text, const std::string& path, const std::string& what,
                  uint64_t largest = 999999999999) {
  if (text.empty() || text.size() > 12 || text.find_first_not_of("0123456789") != std::string::npos)
    throw Error(path, "malformed header: " + what + " '" + text + "' is not a count");
  const uint64_t count = std::stoull(text);
  if (count > largest)
    throw Error(path, "malformed header: " + what + " " + text + " exceeds " + std::to_string(largest));
  return count;
}

// PCL's PCD reader goes on reading header lines after DATA while they are blank, comments or start with a header
// keyword (PCL matches keywords by prefix). Such a line after DATA would change the layout PCL reads behind this
// check's back (a COUNT there is parsed with no check at all), so it is refused.
void check_nothing_after_data(const char* data, size_t size, size_t body, const std::string& path) {
  static const char* const kKeywords[] = {"FIELDS", "COLUMNS", "SIZE",      "TYPE",   "COUNT",
                                          "WIDTH",  "HEIGHT",  "VIEWPOINT", "POINTS", "DATA"};
  for (size_t pos = body; pos < size;) {
    const std::string line = next_line(data, size, pos);
    if (line.empty()) continue;
    std::string word = line;
    const size_t start = word.find_first_not_of(" \t\r\v\f");
    word = start == std::string::npos ? "" : word.substr(start);
    if (word.empty()) return;
    if (word[0] == '#' || word.rfind("VERSION", 0) == 0) continue;
    for (const char* key : kKeywords)
      if (word.rfind(key, 0) == 0)
        throw Error(path, std::string("malformed PCD: a '") + key + "' header line after DATA");
    return;
  }
}

}  // namespace

void check_pcd_layout(const char* data, size_t size, const std::string& path) {
  // PCL holds the point count in an int and a field's COUNT in an int, and multiplies them unchecked.
  constexpr uint64_t kMaxPoints = 0x7fffffff, kMaxCount = 1 << 16, kMaxStep = 1 << 16;
  std::vector<std::string> lines;
  const size_t body = header_lines(data, size, "DATA", path, lines);
  std::vector<std::string> fields, sizes, types, counts;
  uint64_t width = 0, height = 1, points = 0;
  bool has_width = false, has_points = false;
  std::string data_kind;
  std::set<std::string> seen;
  for (const std::string& line : lines) {
    const std::vector<std::string> w = words(line);
    if (w.empty() || w[0][0] == '#') continue;
    // PCL reads a repeated line over what the first one set (a second SIZE moves the offsets, not the types).
    if (!seen.insert(w[0] == "COLUMNS" ? "FIELDS" : w[0]).second)
      throw Error(path, "malformed PCD header: a second '" + w[0] + "' line");
    const std::vector<std::string> rest(w.begin() + 1, w.end());
    if (w[0] == "FIELDS" || w[0] == "COLUMNS") fields = rest;
    else if (w[0] == "SIZE") sizes = rest;
    else if (w[0] == "TYPE") types = rest;
    else if (w[0] == "COUNT") counts = rest;
    else if (w[0] == "WIDTH" && rest.size() == 1) width = to_count(rest[0], path, "WIDTH", kMaxPoints), has_width = true;
    else if (w[0] == "HEIGHT" && rest.size() == 1) height = to_count(rest[0], path, "HEIGHT", kMaxPoints);
    else if (w[0] == "POINTS" && rest.size() == 1)
      points = to_count(rest[0], path, "POINTS", kMaxPoints), has_points = true;
    else if (w[0] == "DATA" && rest.size() == 1) data_kind = rest[0];
    else if (w[0] != "VERSION" && w[0] != "VIEWPOINT")
      throw Error(path, "malformed PCD header: unexpected line '" + line.substr(0, 40) + "'");
  }
  if (fields.empty()) throw Error(path, "malformed PCD header: no FIELDS");
  if (counts.empty()) counts.assign(fields.size(), "1");
  if (sizes.size() != fields.size() || types.size() != fields.size() || counts.size() != fields.size())
    throw Error(path, "malformed PCD header: FIELDS, SIZE, TYPE and COUNT differ in length");
  if (!has_width) throw Error(path, "malformed PCD header: no WIDTH");
  if (!has_points) points = width * height;
  if (points != width * height)
    throw Error(path, "malformed PCD header: POINTS " + std::to_string(points) + " is not WIDTH x HEIGHT");
  if (width * height > kMaxPoints)
    throw Error(path, "malformed PCD header: WIDTH x HEIGHT exceeds " + std::to_string(kMaxPoints) + " points");
  uint64_t step = 0, values = 0;
  for (size_t i = 0; i < fields.size(); ++i) {
    const uint64_t s = to_count(sizes[i], path, "SIZE"), c = to_count(counts[i], path, "COUNT", kMaxCount);
    if (!(s == 1 || s == 2 || s == 4 || s == 8) || types[i].size() != 1 || std::string("IUF").find(types[i]) ==
                                                                                 std::string::npos)
      throw Error(path, "malformed PCD header: field '" + fields[i] + "' has SIZE " + sizes[i] + " TYPE " +
                            types[i]);
    step += s * c;
    values += c;
  }
  if (step > kMaxStep) throw Error(path, "malformed PCD header: " + std::to_string(step) + " bytes a point");
  check_nothing_after_data(data, size, body, path);
  const uint64_t remaining = size - body;
  if (data_kind == "ascii") {
    // Every value takes a digit and a separator at least (the last one's may be the end of the file).
    if (values == 0 || (remaining + 1) / (2 * values) < points)
      throw Error(path, "truncated PCD: " + std::to_string(points) + " points of " + std::to_string(values) +
                            " values need more than the " + std::to_string(remaining) + " bytes after the header");
    return;
  }
  if (data_kind == "binary") {
    if (step == 0 || remaining / step < points)
      throw Error(path, "truncated PCD: " + std::to_string(points) + " points of " + std::to_string(step) +
                            " bytes need more than the " + std::to_string(remaining) + " bytes after the header");
    return;
  }
  if (data_kind == "binary_compressed") {
    if (points == 0) return;
    uint32_t sizes_le[2] = {0, 0};
    if (remaining < 8) throw Error(path, "truncated PCD: no compressed block after the header");
    std::memcpy(sizes_le, data + body, 8);
    if (sizes_le[0] > remaining - 8)
      throw Error(path, "truncated PCD: compressed block of " + std::to_string(sizes_le[0]) + " bytes, only " +
                            std::to_string(remaining - 8) + " in the file");
    if (sizes_le[1] != points * step)
      throw Error(path, "malformed PCD: uncompressed size " + std::to_string(sizes_le[1]) + " is not " +
                            std::to_string(points) + " points x " + std::to_string(step) + " bytes");
    return;
  }
  throw Error(path, "malformed PCD header: DATA '" + data_kind + "' is not ascii, binary or binary_compressed");
}

void check_ply_layout(const char* data, size_t size, const std::string& path) {
  std::vector<std::string> lines;
  const size_t body = header_lines(data, size, "end_header", path, lines);
  if (lines.empty() || lines[0] != "ply") throw Error(path, "not a PLY file: first line is not 'ply'");
  bool binary = false, has_vertex = false, has_x = false, has_y = false, has_z = false;
  // Bytes of the elements up to the vertices, while their properties have fixed sizes (no lists).
  uint64_t fixed_bytes = 0;
  bool fixed = true, in_vertex = false, vertex_done = false;
  uint64_t element_count = 0, element_size = 0;
  auto close_element = [&] {
    if (!vertex_done && fixed) fixed_bytes += element_count * element_size;
    if (in_vertex) vertex_done = true;
  };
  for (size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> w = words(lines[i]);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() < 2) throw Error(path, "malformed PLY header: 'format' without a value");
      if (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian")
        throw Error(path, "malformed PLY header: unknown format '" + w[1] + "'");
      binary = w[1] != "ascii";
    } else if (w[0] == "element") {
      if (w.size() != 3) throw Error(path, "malformed PLY header: '" + lines[i] + "'");
      close_element();
      in_vertex = w[1] == "vertex";
      has_vertex |= in_vertex;
      element_count = to_count(w[2], path, "element count");
      element_size = 0;
    } else if (w[0] == "property") {
      if (w.size() >= 2 && w[1] == "list") {
        // PCL sizes a vertex list from the first vertex and asserts (aborts the process) when a later one is longer.
        if (in_vertex)
          throw Error(path, "PLY vertex property '" + (w.size() == 5 ? w[4] : std::string("?")) +
                                "' is a list, which PCL's reader cannot take: write the points without it");
        fixed = fixed && vertex_done;
        continue;
      }
      if (w.size() != 3) throw Error(path, "malformed PLY header: '" + lines[i] + "'");
      const std::string& t = w[1];
      uint64_t bytes = 0;
      if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") bytes = 1;
      else if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") bytes = 2;
      else if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") bytes = 4;
      else if (t == "double" || t == "float64") bytes = 8;
      else throw Error(path, "malformed PLY header: unknown property type '" + t + "'");
      element_size += bytes;
      if (in_vertex) {
        has_x |= w[2] == "x";
        has_y |= w[2] == "y";
        has_z |= w[2] == "z";
      }
    } else if (w[0] != "end_header") {
      throw Error(path, "malformed PLY header: unexpected line '" + lines[i].substr(0, 40) + "'");
    }
  }
  close_element();
  if (!has_vertex) throw Error(path, "PLY file has no 'vertex' element");
  if (!(has_x && has_y && has_z)) throw Error(path, "PLY vertices lack an x, y or z property");
  if (binary && fixed && size - body < fixed_bytes)
    throw Error(path, "truncated PLY: the vertices need " + std::to_string(fixed_bytes) + " bytes, the file has " +
                          std::to_string(size - body) + " after the header");
}

}  // namespace rosmill::core::io
