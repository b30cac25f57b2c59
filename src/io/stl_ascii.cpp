// ASCII STL: solid / facet normal / outer loop / 3 x vertex / endloop / endfacet / endsolid, keywords in any
// case, any white space (spaces, tabs, CR LF), several solids per file. Numbers go straight from the buffer
// through fast_float; line numbers are counted only when an error is reported.
#include <fast_float/fast_float.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "rosmill/error.hpp"
#include "rosmill/parallel.hpp"
#include "stl_parse.hpp"

namespace rosmill::core::io {
namespace {

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

class AsciiParser {
 public:
  AsciiParser(const char* data, size_t size, const std::string& name, StlSoup& soup)
      : begin_(data), p_(data), end_(data + size), name_(name), soup_(soup) {}
  // A parser over [first, last) of the file that starts at `data` (line numbers count from there).
  AsciiParser(const char* data, const char* first, const char* last, const std::string& name, StlSoup& soup)
      : begin_(data), p_(first), end_(last), name_(name), soup_(soup) {}

  // Parses a chunk of a larger file: facets, and solids ending and beginning. `inside` says whether the chunk
  // starts inside a solid (every chunk but the first starts at a facet) and comes back as the state at its end.
  // Throws on anything unexpected; the caller then parses the whole file sequentially for the exact message.
  void run_chunk(bool& inside) {
    soup_.corners.reserve(3 * ((end_ - p_) / 200 + 1));
    for (skip_space(); p_ != end_; skip_space()) {
      if (inside && accept("facet")) {
        read_facet();
      } else if (inside && accept("endsolid")) {
        skip_line();
        inside = false;
      } else if (!inside && accept("solid")) {
        skip_line();
        ++soup_.solids;
        inside = true;
      } else {
        fail("unexpected " + found());
      }
    }
  }

  void run() {
    // A facet takes ~250 bytes of text in typical files; reserving once avoids most regrowth.
    soup_.corners.reserve(soup_.corners.size() + 3 * ((end_ - p_) / 200 + 1));
    skip_space();
    if (p_ == end_) fail("empty file");
    while (p_ != end_) {
      read_solid();
      skip_space();
    }
    if (soup_.corners.empty()) fail_at(end_, "no triangles (zero facets)");
  }

 private:
  [[noreturn]] void fail_at(const char* where, const std::string& what) const {
    const long line = 1 + std::count(begin_, std::min(where, end_), '\n');
    throw Error(name_ + ":" + std::to_string(line), what);
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(p_, what); }

  void skip_space() {
    while (p_ != end_ && is_space(*p_)) ++p_;
  }
  void skip_line() {
    const void* nl = std::memchr(p_, '\n', end_ - p_);
    p_ = nl ? static_cast<const char*>(nl) + 1 : end_;
  }

  // The next word, for error messages (at most 20 characters).
  std::string next_word() const {
    const char* q = p_;
    while (q != end_ && !is_space(*q) && q - p_ < 20) ++q;
    return std::string(p_, q);
  }
  std::string found() const {
    if (p_ == end_) return "the end of the file (truncated?)";
    const std::string word = next_word();
    // A word cut by the end of the file is the mark of a truncated file, not of a misspelling.
    if (p_ + word.size() == end_) return "'" + word + "' at the end of the file (truncated?)";
    return "'" + word + "'";
  }

  // Consumes `word` (lower case) when it is the next word, in any case; leaves p_ otherwise.
  bool accept(const char* word) {
    skip_space();
    const size_t n = std::strlen(word);
    if (static_cast<size_t>(end_ - p_) < n) return false;
    for (size_t i = 0; i < n; ++i)
      if ((p_[i] | 0x20) != word[i]) return false;
    if (p_ + n != end_ && !is_space(p_[n])) return false;
    p_ += n;
    return true;
  }
  void expect(const char* word, const char* context) {
    if (!accept(word)) fail(std::string("expected '") + word + "' " + context + ", found " + found());
  }

  double number(const char* what) {
    skip_space();
    const char* start = p_;
    if (p_ != end_ && *p_ == '+') ++p_;  // fast_float does not take a leading '+'
    double v = 0.0;
    const auto r = fast_float::from_chars(p_, end_, v);
    if (r.ec != std::errc() || (r.ptr != end_ && !is_space(*r.ptr))) {
      p_ = start;
      fail(std::string("expected a number for ") + what + ", found " + found());
    }
    p_ = r.ptr;
    return v;
  }

  Vec3 triple(const char* what) {
    const double x = number(what);
    const double y = number(what);
    const double z = number(what);
    return Vec3(x, y, z);
  }

  void read_solid() {
    const char* solid_start = p_;
    if (!accept("solid")) fail("not an STL file: expected 'solid', found " + found());
    skip_line();  // the solid's name
    ++soup_.solids;
    for (;;) {
      skip_space();
      if (p_ == end_) fail_at(p_, "unexpected end of file: the solid begun at line " + line_of(solid_start) +
                                      " has no 'endsolid' (truncated file?)");
      if (accept("endsolid")) {
        skip_line();
        return;
      }
      if (!accept("facet")) fail("expected 'facet' or 'endsolid', found " + found());
      read_facet();
    }
  }

  std::string line_of(const char* where) const {
    return std::to_string(1 + std::count(begin_, where, '\n'));
  }

  void read_facet() {
    Vec3 stored = Vec3::Zero();
    if (accept("normal")) {
      // A stored normal is only compared with the corners, so "nan" here is not fatal.
      stored = triple("the facet normal");
    }
    expect("outer", "after 'facet normal'");
    expect("loop", "after 'outer'");
    Vec3 c[3];
    for (int i = 0; i < 3; ++i) {
      expect("vertex", i == 0 ? "after 'outer loop'" : "(a facet has three vertices)");
      const char* at = p_;
      c[i] = triple("a vertex coordinate");
      if (!c[i].allFinite()) fail_at(at, "vertex coordinate is not finite (NaN or infinity)");
    }
    if (accept("vertex")) fail_at(p_ - 6, "facet has more than three vertices (only triangles are allowed)");
    expect("endloop", "after the third vertex");
    expect("endfacet", "after 'endloop'");
    soup_.corners.push_back(c[0]);
    soup_.corners.push_back(c[1]);
    soup_.corners.push_back(c[2]);
    if (stored_normal_disagrees(stored, c[0], c[1], c[2])) ++soup_.stored_normal_mismatches;
  }

  const char* begin_;
  const char* p_;
  const char* end_;
  const std::string& name_;
  StlSoup& soup_;
};

}  // namespace

bool starts_with_solid(const char* data, size_t size) {
  const char* p = data;
  const char* end = data + size;
  while (p != end && is_space(*p)) ++p;
  if (end - p < 5) return false;
  for (int i = 0; i < 5; ++i)
    if ((p[i] | 0x20) != "solid"[i]) return false;
  return p + 5 == end || is_space(p[5]);
}

namespace {

// The start of the first line at or after `p` whose first word is "facet" (any case), or `end`.
const char* next_facet_line(const char* p, const char* end) {
  while (p < end) {
    const void* nl = std::memchr(p, '\n', end - p);
    if (!nl) return end;
    p = static_cast<const char*>(nl) + 1;
    const char* q = p;
    while (q < end && (*q == ' ' || *q == '\t' || *q == '\r')) ++q;
    if (end - q > 5 && (q[0] | 0x20) == 'f' && (q[1] | 0x20) == 'a' && (q[2] | 0x20) == 'c' &&
        (q[3] | 0x20) == 'e' && (q[4] | 0x20) == 't' && is_space(q[5]))
      return p;
  }
  return end;
}

// Large files in chunks on both cores. A valid file has facets only inside solids, so every chunk after the
// first starts inside one and every chunk but the last ends inside one. Returns false (soup untouched) when
// a chunk does not parse: the sequential parser then finds and reports the problem.
bool parse_ascii_chunks(const char* data, size_t size, const std::string& name, StlSoup& soup) {
  constexpr int kChunks = 8;  // a few per core, so an uneven split still balances
  const char* end = data + size;
  std::vector<const char*> bounds{data};
  for (int k = 1; k < kChunks; ++k) {
    const char* b = next_facet_line(std::max(bounds.back(), data + size * k / kChunks), end);
    if (b != end) bounds.push_back(b);
  }
  bounds.push_back(end);
  const int chunks = int(bounds.size()) - 1;
  std::vector<StlSoup> parts(chunks);
  std::vector<char> ok(chunks, 0);
  // One task per chunk, taken by whichever core is free.
  for_each_chunk(chunks, [&](int k) {
    try {
      bool inside = k > 0;
      AsciiParser(data, bounds[k], bounds[k + 1], name, parts[k]).run_chunk(inside);
      ok[k] = inside == (k + 1 < chunks);
    } catch (const Error&) {
      ok[k] = 0;
    }
  });
  size_t corners = 0;
  for (int k = 0; k < chunks; ++k) {
    if (!ok[k]) return false;
    corners += parts[k].corners.size();
  }
  if (corners == 0) return false;
  soup.corners.reserve(soup.corners.size() + corners);
  for (const StlSoup& part : parts) {
    soup.corners.insert(soup.corners.end(), part.corners.begin(), part.corners.end());
    soup.solids += part.solids;
    soup.stored_normal_mismatches += part.stored_normal_mismatches;
  }
  return true;
}

}  // namespace

void parse_ascii(const char* data, size_t size, const std::string& name, StlSoup& soup) {
  constexpr size_t kChunkedFrom = 1 << 22;  // 4 MB: below it, threads cost more than they save
  if (size >= kChunkedFrom && parse_ascii_chunks(data, size, name, soup)) return;
  AsciiParser(data, size, name, soup).run();
}

}  // namespace rosmill::core::io
