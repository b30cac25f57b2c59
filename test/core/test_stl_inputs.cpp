// Bad STL input gets an error naming the file and the problem (never a crash, a hang or an allocation sized
// from the header); awkward but valid files load.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/geometry/mesh_report.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/io/stl.hpp"

using namespace rosmill::core;

namespace {

std::string temp_path(const std::string& name) {
  return testing::TempDir() + "rosmill_test_stl_inputs_" + std::to_string(::getpid()) + "_" + name;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Writes `bytes` to a temporary file, reads it with read_stl and returns the error message ("" if none).
std::string error_of(const std::string& name, const std::string& bytes, std::string* path_out = nullptr) {
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << bytes;
  if (path_out) *path_out = path;
  std::string msg;
  try {
    read_stl(path);
  } catch (const Error& e) {
    msg = e.what();
  }
  std::remove(path.c_str());
  return msg;
}

// Expects read_stl to fail on `bytes` with a message that names the file and contains `problem`.
void expect_error(const std::string& name, const std::string& bytes, const std::string& problem) {
  std::string path;
  const std::string msg = error_of(name, bytes, &path);
  EXPECT_EQ(msg.rfind(path, 0), 0u) << "message does not start with the file name: '" << msg << "'";
  EXPECT_NE(msg.find(problem), std::string::npos) << "expected '" << problem << "' in '" << msg << "'";
}

Mesh load_text(const std::string& text, StlInfo* info = nullptr) {
  return read_stl_buffer(text.data(), text.size(), "text", {}, info);
}

// A binary STL of the given triangles (corners as floats), with `declared` in the count field.
std::string binary_stl(const std::vector<std::array<float, 9>>& tris, uint32_t declared, const char* header = "") {
  std::string out(84, ' ');
  std::memcpy(out.data(), header, std::strlen(header));
  std::memcpy(out.data() + 80, &declared, 4);
  for (const auto& t : tris) {
    float rec[12] = {0, 0, 0};
    std::memcpy(rec + 3, t.data(), 36);
    out.append(reinterpret_cast<const char*>(rec), 48);
    out.append(2, '\0');
  }
  return out;
}

const char* kFacet =
    "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n";

std::string one_facet_solid() { return std::string("solid t\n") + kFacet + "endsolid t\n"; }

// A tetrahedron in ASCII with `fmt` printing each coordinate (for exponent and sign variants).
std::string tetra_ascii(const char* fmt) {
  const double v[4][3] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  const int tri[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  std::string out = "solid tetra\n";
  char buf[64];
  for (const auto& t : tri) {
    out += "facet normal 0 0 0\nouter loop\n";
    for (int i : t) {
      out += "vertex";
      for (int k = 0; k < 3; ++k) {
        std::snprintf(buf, sizeof buf, fmt, v[i][k]);
        out += ' ';
        out += buf;
      }
      out += '\n';
    }
    out += "endloop\nendfacet\n";
  }
  return out + "endsolid tetra\n";
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t pos = 0; (pos = s.find(from, pos)) != std::string::npos; pos += to.size()) s.replace(pos, from.size(), to);
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------------------------------------------

TEST(StlInputs, EmptyFile) { expect_error("empty.stl", "", "empty file"); }

TEST(StlInputs, BlankAsciiFile) { expect_error("blank.stl", " \n\t\r\n", "not an STL file"); }

TEST(StlInputs, HeaderOnly) {
  expect_error("header80.stl", std::string(80, '\0'), "shorter than a binary STL header");
  expect_error("header84.stl", binary_stl({}, 12), "truncated binary STL");
}

TEST(StlInputs, TruncatedBinary) {
  const std::string whole = slurp(ROSMILL_TEST_DATA "/mount_rush.stl");
  expect_error("cut.stl", whole.substr(0, whole.size() - 1000), "truncated binary STL");
  expect_error("cut_odd.stl", whole.substr(0, whole.size() - 7), "15592");
}

TEST(StlInputs, CountLargerThanTheFileIsNotTrusted) {
  // Four billion declared triangles behind two real ones: rejected from the sizes alone, nothing allocated.
  const std::array<float, 9> t = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  expect_error("huge_count.stl", binary_stl({t, t}, 0xffffffffu), "4294967295");
  expect_error("count_plus_one.stl", binary_stl({t, t}, 3), "truncated binary STL");
}

TEST(StlInputs, ZeroTriangles) {
  expect_error("zero.stl", binary_stl({}, 0), "zero triangles");
  expect_error("zero_ascii.stl", "solid empty\nendsolid empty\n", "no triangles");
}

TEST(StlInputs, MalformedNumber) {
  expect_error("malformed.stl", replace_all(one_facet_solid(), "vertex 1 0 0", "vertex 1 0x 0"),
               "expected a number for a vertex coordinate, found '0x'");
  expect_error("comma.stl", replace_all(one_facet_solid(), "vertex 1 0 0", "vertex 1,5 0 0"), ":5: expected a number");
}

TEST(StlInputs, MissingNumber) {
  expect_error("missing.stl", replace_all(one_facet_solid(), "vertex 1 0 0", "vertex 1 0"),
               ":6: expected a number for a vertex coordinate, found 'vertex'");
  expect_error("missing_normal.stl", replace_all(one_facet_solid(), "normal 0 0 1", "normal 0 0"),
               "expected a number for the facet normal, found 'outer'");
}

TEST(StlInputs, FourVerticesInAFacet) {
  expect_error("quad.stl", replace_all(one_facet_solid(), "  vertex 0 1 0\n", "  vertex 0 1 0\n  vertex 1 1 0\n"),
               ":7: facet has more than three vertices");
}

TEST(StlInputs, TwoVerticesInAFacet) {
  expect_error("two.stl", replace_all(one_facet_solid(), "  vertex 0 1 0\n", ""), "expected 'vertex'");
}

TEST(StlInputs, TruncatedAscii) {
  const std::string whole = slurp(ROSMILL_TEST_DATA "/wheel_in_box.stl");
  // Cut anywhere (inside a number, a keyword, between facets): always an error saying it may be truncated.
  for (size_t keep : {whole.size() / 3, whole.size() / 2 + 17, whole.size() - 20, whole.size() - 40}) {
    SCOPED_TRACE(keep);
    expect_error("cut.stl", whole.substr(0, keep), "truncated");
  }
  expect_error("no_endsolid.stl", std::string("solid t\n") + kFacet, "has no 'endsolid' (truncated file?)");
}

TEST(StlInputs, NonFiniteCoordinates) {
  expect_error("nan.stl", replace_all(one_facet_solid(), "vertex 1 0 0", "vertex nan 0 0"), ":5: vertex coordinate is not finite");
  expect_error("inf.stl", replace_all(one_facet_solid(), "vertex 1 0 0", "vertex 1 -inf 0"), "not finite");
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  expect_error("nan_bin.stl", binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, nan, 1, 0, 0, 0, 1, 0}}, 2),
               "triangle 1 (byte 134) has a coordinate that is not finite");
  expect_error("inf_bin.stl", binary_stl({{0, 0, 0, 1, inf, 0, 0, 1, 0}}, 1), "triangle 0");
  // Triangles are decoded in batches: the error names the triangle inside its batch (here the last corner's z
  // of triangle 45, in the second batch of 32), not the batch.
  std::vector<std::array<float, 9>> many(70, {0, 0, 0, 1, 0, 0, 0, 1, 0});
  many[45][8] = -inf;
  many[60][0] = nan;
  expect_error("nan_bin_batch.stl", binary_stl(many, 70), "triangle 45 (byte 2334)");
}

TEST(StlInputs, BinaryNegativeZeroWeldsWithZeroAndANonFiniteNormalIsJudgedNotRefused) {
  // Two triangles sharing the edge (0,0,0)-(1,0,0), the shared corners written once with -0 components.
  std::string bytes = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, -0.0f, -0.0f, -0.0f, -0.0f, -0.0f, 0, -1, 0}}, 2);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bytes[84], &nan, sizeof nan);  // the first triangle's stored normal
  StlInfo info;
  const Mesh m = read_stl_buffer(bytes.data(), bytes.size(), "zeros.stl", {}, &info);
  EXPECT_EQ(m.vertices.size(), 4u);  // (0,0,0), (1,0,0), (0,1,0), (0,-1,0)
  EXPECT_TRUE(m.edges.size() == 5u && m.faces[1][0] == m.faces[0][1] && m.faces[1][1] == m.faces[0][0]);
  EXPECT_EQ(info.stored_normal_mismatches, 1u);
  for (const Vec3& v : m.vertices)
    for (int i = 0; i < 3; ++i) EXPECT_FALSE(v[i] == 0.0 && std::signbit(v[i])) << "-0 kept at vertex " << v.transpose();
}

TEST(StlInputs, NotAnStlFile) {
  expect_error("text.stl", "Hello, this is a README, not a mesh.\nSecond line.\n", "not an STL file");
  expect_error("long_text.stl", std::string(5000, 'x'), "not an STL file");
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string(3000, '\x07');
  expect_error("image.stl", png, "not an STL file");
  expect_error("garbage_solid.stl", "solid x\nthis is not a facet\n", ":2: expected 'facet' or 'endsolid', found 'this'");
}

TEST(StlInputs, MissingFileAndDirectory) {
  const std::string missing = temp_path("does_not_exist.stl");
  try {
    read_stl(missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), missing + ": no such file");
  }
  const std::string dir = testing::TempDir();
  try {
    read_stl(dir);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir + ": is a directory"), std::string::npos) << e.what();
  }
}

TEST(StlInputs, CorruptGzip) {
  std::string gz = "\x1f\x8b\x08";
  gz += std::string(100, 'z');
  expect_error("bad.stl.gz", gz, "gzip");
}

// ---------------------------------------------------------------------------------------------------------------
// Awkward but valid input
// ---------------------------------------------------------------------------------------------------------------

TEST(StlInputs, CrlfUpperCaseAndTabsLoadTheSame) {
  const std::string plain = slurp(ROSMILL_TEST_DATA "/failedinpycam.stl");
  const Mesh reference = load_text(plain);
  ASSERT_EQ(reference.face_count(), 428u);
  std::string upper;
  for (char c : plain) upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const std::string variants[] = {replace_all(plain, "\n", "\r\n"), upper, replace_all(plain, " ", "\t"),
                                  replace_all(replace_all(plain, " ", " \t "), "\n", "\r\n")};
  for (const std::string& text : variants) {
    const Mesh m = load_text(text);
    EXPECT_EQ(m.faces, reference.faces);
    EXPECT_EQ(m.vertices, reference.vertices);
  }
}

TEST(StlInputs, ExponentNotationAndSigns) {
  const Mesh plain = load_text(tetra_ascii("%g"));
  for (const char* fmt : {"%e", "%E", "%.3e", "%+.4f", "%+e"}) {
    SCOPED_TRACE(fmt);
    const Mesh m = load_text(tetra_ascii(fmt));
    EXPECT_EQ(m.vertices, plain.vertices);
    EXPECT_EQ(m.faces, plain.faces);
  }
  const MeshReport r = report(plain);
  EXPECT_TRUE(r.closed);
  EXPECT_NEAR(r.volume, 1000.0 / 6.0, 1e-9);
}

TEST(StlInputs, SeveralSolidsInOneFile) {
  const std::string a = slurp(ROSMILL_TEST_DATA "/failedinpycam.stl");
  const std::string b = slurp(ROSMILL_TEST_DATA "/pycam-textbox.stl");
  StlInfo info;
  const Mesh m = load_text(a + b + tetra_ascii("%g"), &info);
  EXPECT_EQ(info.solids, 3u);
  EXPECT_EQ(m.face_count(), 428u + 1444u + 4u);
}

TEST(StlInputs, NoFinalNewlineAndNamelessEndsolid) {
  StlInfo info;
  const Mesh m = load_text(std::string("  \n solid\n") + kFacet + "endsolid", &info);
  EXPECT_EQ(m.face_count(), 1u);
  EXPECT_TRUE(info.ascii);
}

TEST(StlInputs, TrailingBytesAfterABinaryBody) {
  const std::string rush = slurp(ROSMILL_TEST_DATA "/mount_rush.stl");
  StlInfo info;
  Mesh m = read_stl_buffer((rush + std::string(123, '\x5a')).data(), rush.size() + 123, "rush+", {}, &info);
  EXPECT_EQ(m.face_count(), 15592u);
  EXPECT_FALSE(info.ascii);
  // A header that begins with "solid" and trailing bytes: still binary, once ASCII parsing fails.
  const std::string cav = slurp(ROSMILL_TEST_DATA "/ktoolcav.stl") + "solid trailing text\n";
  m = read_stl_buffer(cav.data(), cav.size(), "ktoolcav+", {}, &info);
  EXPECT_EQ(m.face_count(), 4090u);
  EXPECT_FALSE(info.ascii);
}

TEST(StlInputs, BinaryHeaderStartingWithSolid) {
  const std::array<float, 9> t = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::string bytes = binary_stl({t, t, t}, 3, "solid looks like ascii");
  StlInfo info;
  const Mesh m = read_stl_buffer(bytes.data(), bytes.size(), "solid_header", {}, &info);
  EXPECT_FALSE(info.ascii);
  EXPECT_EQ(m.face_count(), 3u);
}

TEST(StlInputs, DegenerateTrianglesAreKeptAndCounted) {
  std::string text = tetra_ascii("%g");
  const std::string degenerate =
      "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 10 0 0\nendloop\nendfacet\n"   // repeated
      "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 5 0 0\nvertex 10 0 0\nendloop\nendfacet\n";  // collinear
  text.insert(text.find("endsolid"), degenerate);
  const Mesh m = load_text(text);
  EXPECT_EQ(m.face_count(), 6u);
  const MeshReport r = report(m);
  EXPECT_EQ(r.degenerate, 2u);
  EXPECT_NEAR(r.area, report(load_text(tetra_ascii("%g"))).area, 1e-12);
}

TEST(StlInputs, StoredNormalsAreCheckedNotTrusted) {
  // The tetrahedron's first facet (0, 2, 1) faces -z: a stored +z normal disagrees, a zero one is not judged.
  std::string text = tetra_ascii("%g");
  StlInfo info;
  load_text(text, &info);
  EXPECT_EQ(info.stored_normal_mismatches, 0u);
  text.replace(text.find("facet normal 0 0 0"), 18, "facet normal 0 0 1");
  const Mesh m = load_text(text, &info);
  EXPECT_EQ(info.stored_normal_mismatches, 1u);
  EXPECT_NEAR(m.normals[0].z(), -1.0, 1e-12);  // recomputed from the corners
  text.replace(text.find("facet normal 0 0 0"), 18, "facet normal 0 -1 0.1");  // 5.7 degrees off: tolerated
  load_text(text, &info);
  EXPECT_EQ(info.stored_normal_mismatches, 1u);
}

TEST(StlInputs, StoredNormalsOfRealFilesAgree) {
  StlInfo info;
  read_stl(ROSMILL_TEST_DATA "/ktoolcav.stl", {}, &info);
  EXPECT_EQ(info.stored_normal_mismatches, 0u);
  read_stl(ROSMILL_TEST_DATA "/wheel_in_box.stl", {}, &info);
  EXPECT_EQ(info.stored_normal_mismatches, 0u);
}

TEST(StlInputs, WeldToleranceJoinsNearbyCorners) {
  // featuretype.STL repeats corners with float noise: exact welding leaves seams, 1e-5 inch closes them.
  const Mesh exact = read_stl(ROSMILL_TEST_DATA "/featuretype.STL");
  EXPECT_EQ(report(exact).open_edges, 576u);
  StlReadOptions options;
  options.units = Units::Inch;
  options.weld.tolerance = 1e-5 * 25.4;  // millimetres
  const Mesh welded = read_stl(ROSMILL_TEST_DATA "/featuretype.STL", options);
  const MeshReport r = report(welded);
  EXPECT_EQ(r.open_edges, 0u);
  EXPECT_TRUE(r.closed);
  EXPECT_LT(welded.vertex_count(), exact.vertex_count());
}

TEST(StlInputs, RoundTripsOfARealAsciiModel) {
  const Mesh original = read_stl(ROSMILL_TEST_DATA "/wheel_in_box.stl");
  for (bool ascii : {true, false}) {
    SCOPED_TRACE(ascii ? "ascii" : "binary");
    const std::string path = temp_path(ascii ? "wheel_ascii.stl" : "wheel_binary.stl");
    write_stl(path, original, ascii);
    StlInfo info;
    const Mesh back = read_stl(path, {}, &info);
    std::remove(path.c_str());
    EXPECT_EQ(info.ascii, ascii);
    EXPECT_EQ(back.faces, original.faces);
    ASSERT_EQ(back.vertex_count(), original.vertex_count());
    for (size_t v = 0; v < back.vertex_count(); ++v)
      ASSERT_LE((back.vertices[v] - original.vertices[v]).norm(), ascii ? 0.0 : 1e-4);
  }
}

TEST(StlInputs, WritingToAMissingDirectoryFails) {
  const std::string path = "/nonexistent_dir_rosmill/out.stl";
  try {
    write_stl(path, make_primitive("cube"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": cannot write"), std::string::npos) << e.what();
  }
}
