// The setup sheet (sheet/setup_sheet.hpp): the picture of a setup is a PNG cairo reads back at the size asked, the
// drawing fitted inside a white margin; each operation's toolpaths in its colour and no colour of an operation
// that draws nothing; the fixture in its colour only when there is one; faces turned away left out and the near
// solid painted over the far one; a mesh of 300k triangles drawn in under a second. The HTML holds every setup
// with its picture inline (a PNG of the size it declares), its face down, fixture, work offset, program, and
// operations with their tools, times and colours, every text from the job escaped; writing it to a folder that
// does not exist is refused naming the file.
#include <cairo.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "error_of.hpp"
#include "rosmill/error.hpp"
#include "rosmill/geometry/placement.hpp"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/sheet/setup_sheet.hpp"

using namespace rosmill::core;
using namespace rosmill::core::sheet;

namespace {

// ---- reading the pictures back ------------------------------------------------------------------------------

struct Picture {
  int width = 0, height = 0;
  std::vector<uint32_t> rgb;  // 0xRRGGBB, rows top to bottom

  uint32_t at(int x, int y) const { return rgb[static_cast<size_t>(y) * width + x]; }
};

struct PngReader {
  const std::vector<unsigned char>* bytes;
  size_t at = 0;
};

cairo_status_t read_png(void* closure, unsigned char* data, unsigned int length) {
  auto* r = static_cast<PngReader*>(closure);
  if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
  std::copy_n(r->bytes->begin() + static_cast<std::ptrdiff_t>(r->at), length, data);
  r->at += length;
  return CAIRO_STATUS_SUCCESS;
}

// The PNG decoded by cairo (an independent reader of what cairo wrote); fails the test when it does not decode.
Picture decode(const std::vector<unsigned char>& png) {
  Picture p;
  const unsigned char signature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(png.size() > 8 && std::equal(signature, signature + 8, png.begin())) << "no PNG signature";
  PngReader reader{&png};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(read_png, &reader);
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << cairo_status_to_string(cairo_surface_status(s));
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    p.width = cairo_image_surface_get_width(s);
    p.height = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x)
        p.rgb.push_back(reinterpret_cast<const uint32_t*>(data + static_cast<size_t>(y) * stride)[x] & 0xffffff);
  }
  cairo_surface_destroy(s);
  return p;
}

uint32_t hex(const std::string& colour) { return static_cast<uint32_t>(std::stoul(colour.substr(1), nullptr, 16)); }

int channel(uint32_t c, int i) { return static_cast<int>(c >> (16 - 8 * i) & 0xff); }

bool near(uint32_t a, uint32_t b, int tolerance) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(channel(a, i) - channel(b, i)) > tolerance) return false;
  return true;
}

size_t count(const Picture& p, const std::function<bool(uint32_t)>& is) {
  return static_cast<size_t>(std::count_if(p.rgb.begin(), p.rgb.end(), is));
}

size_t count_colour(const Picture& p, const std::string& colour, int tolerance = 6) {
  const uint32_t c = hex(colour);
  return count(p, [&](uint32_t v) { return near(v, c, tolerance); });
}

constexpr uint32_t kWhite = 0xffffff;
// The fixture is brown (red over green over blue), the part grey-blue (blue the most): told apart by hue, whatever
// the shading.
bool brown(uint32_t c) { return channel(c, 0) > 1.2 * channel(c, 1) && channel(c, 1) > 1.3 * channel(c, 2); }
bool grey_blue(uint32_t c) { return c != kWhite && channel(c, 2) > channel(c, 0) + 8; }

// ---- a small job made by hand ---------------------------------------------------------------------------------

Box3 box(const Vec3& lo, const Vec3& hi) {
  Box3 b;
  b.add(lo);
  b.add(hi);
  return b;
}

// A vise around the 60 mm cube, jaws closing along y, gripping its lowest 15 mm.
fixture::Fixture vise() {
  fixture::Fixture f;
  f.description = "vise 100 mm, jaws across y, grip 15 mm";
  f.boxes.push_back({"vise fixed jaw", box(Vec3(-20, 60, -10), Vec3(80, 80, 15))});
  f.boxes.push_back({"vise moving jaw", box(Vec3(-20, -20, -10), Vec3(80, 0, 15))});
  return f;
}

// A zig-zag of feeds at height z over [x0, x1] x [y0, y1], reached by a rapid and a plunge.
Toolpath zigzag(double x0, double x1, double y0, double y1, double z) {
  Toolpath tp;
  tp.strategy = "raster";
  tp.start = Vec3(30, 30, 100);
  ToolpathPass pass;
  pass.name = "layer 1";
  pass.moves.push_back({Vec3(x0, y0, z + 5), MoveType::Rapid, 0});
  pass.moves.push_back({Vec3(x0, y0, z), MoveType::Plunge, 300});
  bool right = true;
  for (double y = y0; y <= y1 + 1e-9; y += 10) {
    pass.moves.push_back({Vec3(right ? x0 : x1, y, z), MoveType::Feed, 1000});
    pass.moves.push_back({Vec3(right ? x1 : x0, y, z), MoveType::Feed, 1000});
    right = !right;
  }
  pass.moves.push_back({Vec3(x0, y1, 100), MoveType::Rapid, 0});
  tp.passes.push_back(pass);
  return tp;
}

Tool tool(int id, const std::string& name, double diameter) {
  Tool t;
  t.id = id;
  t.name = name;
  t.cutter = Cutter::flat(diameter);
  t.cutter.flute_length = 22;
  t.stick_out = 35;
  t.holder_diameter = 32;
  return t;
}

job::OperationReport operation(const std::string& name, const std::string& strategy, const Tool& t, size_t setup,
                               double time_s) {
  job::OperationReport op;
  op.name = name;
  op.strategy = strategy;
  op.tool = "T" + std::to_string(t.id);
  op.tool_used = t;
  op.setup_index = setup;
  op.time_s = time_s;
  return op;
}

struct Sample {
  Mesh part = make_primitive("cube");  // [0, 60]^3
  job::JobReport report;
  SheetJob job;
};

// Two setups of the cube: the top (three operations, the last with nothing to cut), then turned over for the
// bottom with the work offset G55 at a registered place.
std::unique_ptr<Sample> sample() {
  auto s = std::make_unique<Sample>();
  job::JobReport& r = s->report;
  r.operations.push_back(operation("rough top", "rough", tool(3, "flat 10", 10), 0, 754));
  r.operations.push_back(operation("finish <script>alert(1)</script>", "raster", tool(5, "ball 6", 6), 0, 125));
  r.operations.push_back(operation("rest corners", "rest", tool(7, "flat 3", 3), 0, 0));
  r.operations.back().nothing_to_cut = true;
  r.operations.push_back(operation("face bottom", "rough", tool(3, "flat 10", 10), 1, 2846));

  job::SetupReport top;
  top.name = "top";
  top.face_down = "-Z";
  top.fixture = vise();
  top.datum = job::Datum::TopCentre;
  top.datum_point = Vec3(30, 30, 60);
  top.operations = {0, 1, 2};
  top.time_s = 879;
  top.program = "/some/where/out/cube_setup1.ngc";
  r.setups.push_back(top);

  job::SetupReport bottom;
  bottom.name = "bottom";
  bottom.direction = -Vec3::UnitZ();
  bottom.face_down = "+Z";
  // Turned over about x: (x, y, z) -> (x, 60 - y, 60 - z), the cube in the same place.
  bottom.frame = named_setup("-Z");
  bottom.frame.placement.pose = Eigen::Translation3d(0, 60, 60) * Eigen::AngleAxisd(M_PI, Vec3::UnitX());
  bottom.fixture = vise();
  bottom.fixture.description = "vise 100 mm, soft jaws";
  bottom.datum = job::Datum::Corner;
  bottom.datum_point = Vec3(0, 60, 0);
  gcode::WorkOffset g55;
  g55.index = 2;
  g55.origin = Vec3(120.5, 80, -250.25);
  bottom.work_offset = g55;
  bottom.operations = {3};
  bottom.time_s = 2846;
  r.setups.push_back(bottom);

  r.time_s = 3725;  // 1:02:05
  s->job.title = "jobs/cube.yaml";
  s->job.report = &s->report;
  s->job.part = &s->part;
  s->job.toolpaths.resize(4);
  s->job.toolpaths[0] = {zigzag(0, 60, 0, 60, 55)};
  s->job.toolpaths[1] = {zigzag(5, 55, 5, 55, 60)};
  s->job.toolpaths[3] = {zigzag(0, 60, 0, 60, 58)};
  return s;
}

std::vector<const Job*> operations_of(const Sample& s, size_t setup) {
  std::vector<const Job*> ops;
  for (size_t op : s.report.setups[setup].operations) ops.push_back(&s.job.toolpaths[op]);
  return ops;
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

std::vector<unsigned char> base64_decode(const std::string& text) {
  static const std::string kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  uint32_t bits = 0;
  int held = 0;
  for (char c : text) {
    if (c == '=') break;
    const size_t v = kDigits.find(c);
    if (v == std::string::npos) {
      ADD_FAILURE() << "not base64: " << c;
      return {};
    }
    bits = bits << 6 | static_cast<uint32_t>(v);
    held += 6;
    if (held >= 8) {
      held -= 8;
      out.push_back(static_cast<unsigned char>(bits >> held & 0xff));
    }
  }
  return out;
}

// The PNG data of each <img> of the sheet.
std::vector<std::vector<unsigned char>> inline_pictures(const std::string& html) {
  const std::string lead = "<img src=\"data:image/png;base64,";
  std::vector<std::vector<unsigned char>> pictures;
  for (size_t at = html.find(lead); at != std::string::npos; at = html.find(lead, at + 1)) {
    const size_t begin = at + lead.size(), end = html.find('"', begin);
    pictures.push_back(base64_decode(html.substr(begin, end - begin)));
  }
  return pictures;
}

// The table row of the sheet that holds `text`.
std::string row_of(const std::string& html, const std::string& text) {
  const size_t at = html.find(text);
  if (at == std::string::npos) return "";
  const size_t begin = html.rfind("<tr>", at), end = html.find("</tr>", at);
  return html.substr(begin, end - begin);
}

// Only the corners of a box, as triangles of no area: a mesh with the box's extent (the same fit of the picture)
// that draws nothing.
Mesh corners_only(const Box3& b) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) {
    const Vec3 c((i & 1 ? b.max : b.min).x(), (i & 2 ? b.max : b.min).y(), (i & 4 ? b.max : b.min).z());
    corners.insert(corners.end(), {c, c, c});
  }
  return build_mesh(corners);
}

}  // namespace

// ---- the picture ------------------------------------------------------------------------------------------------

TEST(SetupPicture, IsAPngOfTheSizeAskedFittedInsideAWhiteMargin) {
  const auto s = sample();
  const std::vector<unsigned char> png = setup_picture_png(s->part, vise(), operations_of(*s, 0), 320, 200);
  const Picture p = decode(png);
  ASSERT_EQ(p.width, 320);
  ASSERT_EQ(p.height, 200);
  int x0 = p.width, x1 = -1, y0 = p.height, y1 = -1;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      if (p.at(x, y) != kWhite) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  // Nothing touches the border; the drawing fills the picture in one direction (it keeps its proportions).
  EXPECT_GE(x0, 4);
  EXPECT_GE(y0, 4);
  EXPECT_LE(x1, p.width - 5);
  EXPECT_LE(y1, p.height - 5);
  EXPECT_TRUE(x1 - x0 > 0.8 * p.width || y1 - y0 > 0.8 * p.height) << x0 << ".." << x1 << " x " << y0 << ".." << y1;

  if (const char* dump = std::getenv("ROSMILL_SHEET_PICTURE")) {  // to look at it
    const std::vector<unsigned char> big = setup_picture_png(s->part, vise(), operations_of(*s, 0), 900, 600);
    std::ofstream(dump, std::ios::binary).write(reinterpret_cast<const char*>(big.data()), big.size());
  }
}

TEST(SetupPicture, DrawsEachOperationInItsColourAndNothingForAnOperationWithoutToolpaths) {
  const auto s = sample();
  const Picture with = decode(setup_picture_png(s->part, vise(), operations_of(*s, 0), 600, 400));
  EXPECT_GT(count_colour(with, operation_colour(0)), 100u);
  EXPECT_GT(count_colour(with, operation_colour(1)), 100u);
  EXPECT_EQ(count_colour(with, operation_colour(2)), 0u) << "the operation with nothing to cut draws nothing";

  // The same setup without toolpaths: no colour of the palette anywhere.
  const Job none;
  const Picture without = decode(setup_picture_png(s->part, vise(), {&none, &none, nullptr}, 600, 400));
  for (size_t k = 0; k < 8; ++k) EXPECT_EQ(count_colour(without, operation_colour(k)), 0u) << k;

  // The cuts lie over the part: across the screen, within the part drawn in the same picture (the view's
  // horizontal does not depend on height).
  int part_x0 = with.width, part_x1 = 0;
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width; ++x)
      if (grey_blue(with.at(x, y))) part_x0 = std::min(part_x0, x), part_x1 = std::max(part_x1, x);
  const uint32_t first = hex(operation_colour(0));
  for (int y = 0; y < with.height; ++y)
    for (int x = 0; x < with.width; ++x)
      if (near(with.at(x, y), first, 6)) {
        ASSERT_GE(x, part_x0 - 2);
        ASSERT_LE(x, part_x1 + 2);
      }
}

TEST(SetupPicture, PaletteIsFixedDistinctAndCycles) {
  std::set<std::string> colours;
  for (size_t k = 0; k < 8; ++k) {
    const std::string c = operation_colour(k);
    ASSERT_EQ(c.size(), 7u);
    ASSERT_EQ(c[0], '#');
    EXPECT_EQ(c.find_first_not_of("0123456789abcdef", 1), std::string::npos) << c;
    EXPECT_FALSE(brown(hex(c))) << c << " would read as the fixture";
    for (const std::string& other : colours) EXPECT_FALSE(near(hex(c), hex(other), 60)) << c << " " << other;
    colours.insert(c);
  }
  EXPECT_EQ(operation_colour(8), operation_colour(0));
  EXPECT_EQ(operation_colour(13), operation_colour(5));
}

TEST(SetupPicture, FixtureColourOnlyWithAFixture) {
  const auto s = sample();
  const Picture held = decode(setup_picture_png(s->part, vise(), {}, 600, 400));
  const Picture free = decode(setup_picture_png(s->part, fixture::Fixture{}, {}, 600, 400));
  EXPECT_GT(count(held, brown), 5000u);
  EXPECT_EQ(count(free, brown), 0u);
  EXPECT_GT(count(held, grey_blue), 5000u);
  EXPECT_GT(count(free, grey_blue), 5000u);
  // Nothing but the part and the white around it.
  EXPECT_EQ(count(free, [](uint32_t c) { return c != kWhite && !grey_blue(c); }), 0u);
}

TEST(SetupPicture, ACubeShowsThreeFlatShadedFaces) {
  const Picture p = decode(setup_picture_png(make_primitive("cube"), fixture::Fixture{}, {}, 300, 300));
  std::map<uint32_t, size_t> shades;
  for (uint32_t c : p.rgb)
    if (c != kWhite) ++shades[c];
  ASSERT_EQ(shades.size(), 3u) << "top, front and right; solids are filled without blending at their edges";
  size_t total = 0;
  for (const auto& [c, n] : shades) {
    EXPECT_TRUE(grey_blue(c)) << std::hex << c;
    total += n;
  }
  for (const auto& [c, n] : shades) EXPECT_GT(n, total / 6) << std::hex << c;
}

TEST(SetupPicture, FacesTurnedAwayAreLeftOut) {
  // One triangle on z = 0 with its normal up (towards the viewer above) and the same turned over.
  const std::vector<Vec3> up = {Vec3(0, 0, 0), Vec3(50, 0, 0), Vec3(0, 50, 0)};
  const std::vector<Vec3> down = {up[0], up[2], up[1]};
  EXPECT_GT(count(decode(setup_picture_png(build_mesh(up), fixture::Fixture{}, {}, 200, 200)), grey_blue), 5000u);
  EXPECT_EQ(count(decode(setup_picture_png(build_mesh(down), fixture::Fixture{}, {}, 200, 200)), grey_blue), 0u);
}

TEST(SetupPicture, TheNearSolidCoversTheFarOne) {
  // A block (the fixture) standing on a plate (the part), and the plate's corners alone: the same extent (the same
  // fit) without a face.
  const Box3 plate = box(Vec3(0, 0, 0), Vec3(100, 100, 2));
  fixture::Fixture block;
  block.boxes.push_back({"block", box(Vec3(45, 45, 2), Vec3(55, 55, 12))});
  const Picture on_plate = decode(setup_picture_png(build_mesh(box_corners(plate)), block, {}, 400, 400));
  const Picture alone = decode(setup_picture_png(corners_only(plate), block, {}, 400, 400));
  EXPECT_EQ(count(alone, grey_blue), 0u);
  const size_t block_pixels = count(alone, brown);
  EXPECT_GT(block_pixels, 300u);
  // Painted over the plate it stands on. Far to near by pieces is not exact where two solids touch: a piece of the
  // plate under the block's foot may come later than the block's lowest piece and take a pixel or two there.
  EXPECT_LE(count(on_plate, brown), block_pixels);
  EXPECT_GE(count(on_plate, brown), 0.98 * block_pixels);
  EXPECT_GT(count(on_plate, grey_blue), 10 * block_pixels);

  // The block under the plate: the plate hides it.
  fixture::Fixture under;
  under.boxes.push_back({"under", box(Vec3(45, 45, -12), Vec3(55, 55, -2))});
  const Picture hidden = decode(setup_picture_png(build_mesh(box_corners(plate)), under, {}, 400, 400));
  EXPECT_EQ(count(hidden, brown), 0u);
}

TEST(SetupPicture, EmptySceneIsWhite) {
  const Picture p = decode(setup_picture_png(Mesh{}, fixture::Fixture{}, {nullptr}, 64, 48));
  ASSERT_EQ(p.width, 64);
  EXPECT_EQ(count(p, [](uint32_t c) { return c != kWhite; }), 0u);
}

TEST(SetupPicture, RefusesSizesOutside16To4096) {
  const Mesh cube = make_primitive("cube");
  for (const auto& size : std::vector<std::pair<int, int>>{{15, 100}, {100, 15}, {4097, 100}, {100, 4097},
                                                           {0, 0}, {-20, 100}}) {
    const int w = size.first, h = size.second;  // a lambda may not capture a structured binding (C++17)
    const std::string e = error_of([&] { setup_picture_png(cube, fixture::Fixture{}, {}, w, h); });
    EXPECT_NE(e.find("setup picture"), std::string::npos) << w << " x " << h << ": " << e;
    EXPECT_NE(e.find(w < 16 || w > 4096 ? "width" : "height"), std::string::npos) << e;
  }
  EXPECT_EQ(decode(setup_picture_png(cube, fixture::Fixture{}, {}, 16, 16)).width, 16);
  EXPECT_EQ(decode(setup_picture_png(cube, fixture::Fixture{}, {}, 4096, 16)).width, 4096);
}

// A large part is drawn whole (its time is printed and recorded, not asserted: a loaded or sanitized machine is
// slower; the figure on an idle machine is in bench/RESULTS.md).
TEST(SetupPicture, Draws300kTriangles) {
  // A sphere of radius 40 in 300 rings of 500 segments: 299,000 triangles, outward.
  const int rings = 300, segments = 500;
  auto at = [](int i, int j) {
    const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
    return Vec3(40 * std::sin(theta) * std::cos(phi), 40 * std::sin(theta) * std::sin(phi), 40 * std::cos(theta));
  };
  std::vector<Vec3> corners;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const Vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i > 0) corners.insert(corners.end(), {a, b, d});
      if (i + 1 < rings) corners.insert(corners.end(), {b, c, d});
    }
  const Mesh sphere = build_mesh(corners);
  ASSERT_GT(sphere.face_count(), 290000u);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<unsigned char> png = setup_picture_png(sphere, vise(), {}, 900, 600);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Picture p = decode(png);
  RecordProperty("seconds", std::to_string(seconds));
  std::printf("300k triangles: %.3f s\n", seconds);
  EXPECT_GT(count(p, grey_blue), 100000u);
  // A smooth sphere: many shades, none of them a hole to the white behind it inside its outline.
  std::set<uint32_t> shades;
  for (uint32_t c : p.rgb)
    if (grey_blue(c)) shades.insert(c);
  EXPECT_GT(shades.size(), 50u);
}

// ---- the sheet --------------------------------------------------------------------------------------------------

TEST(SetupSheet, HoldsEverySetupWithItsFactsAndPicture) {
  const auto s = sample();
  const std::string html = setup_sheet_html(s->job);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(occurrences(html, "<img src=\"data:image/png;base64,"), 2u);
  // Self-contained: nothing fetched from elsewhere.
  for (const char* outside : {"http:", "https:", "<link", "<script", "src=\"/", "url("})
    EXPECT_EQ(html.find(outside), std::string::npos) << outside;
  EXPECT_NE(html.find("@media"), std::string::npos);
  EXPECT_NE(html.find("page-break-before"), std::string::npos);

  EXPECT_NE(html.find("jobs/cube.yaml"), std::string::npos);
  EXPECT_NE(html.find("1:02:05"), std::string::npos) << "the job's time";
  EXPECT_NE(html.find("Setup 1 of 2: top"), std::string::npos);
  EXPECT_NE(html.find("Setup 2 of 2: bottom"), std::string::npos);
  EXPECT_NE(row_of(html, "Face down").find("-Z"), std::string::npos);
  EXPECT_NE(html.find("vise 100 mm, jaws across y, grip 15 mm"), std::string::npos);
  EXPECT_NE(html.find("vise 100 mm, soft jaws"), std::string::npos);
  EXPECT_NE(html.find("vise fixed jaw: 100 &times; 20 &times; 25 mm"), std::string::npos);
  EXPECT_NE(html.find("top-centre at (30, 30, 60)"), std::string::npos);
  EXPECT_NE(html.find("corner at (0, 60, 0)"), std::string::npos);
  EXPECT_NE(html.find("G54 as set on the controller"), std::string::npos);
  EXPECT_NE(html.find("G55 at machine X120.5 Y80 Z-250.25"), std::string::npos);
  EXPECT_NE(row_of(html, "Program").find("cube_setup1.ngc"), std::string::npos);
  EXPECT_EQ(html.find("/some/where"), std::string::npos) << "the file's name, not where it was written";
  EXPECT_NE(html.find("not written"), std::string::npos);

  // Each operation in its row with its tool, time and the colour of its position in its setup.
  const std::string rough = row_of(html, "rough top");
  EXPECT_NE(rough.find(operation_colour(0)), std::string::npos) << rough;
  EXPECT_NE(rough.find("T3 flat 10"), std::string::npos);
  EXPECT_NE(rough.find("12:34"), std::string::npos) << "754 s";
  EXPECT_NE(rough.find(">35<"), std::string::npos) << "stick-out";
  EXPECT_NE(rough.find(">32<"), std::string::npos) << "holder";
  EXPECT_NE(rough.find(">22<"), std::string::npos) << "flute length";
  const std::string finish = row_of(html, "finish ");
  EXPECT_NE(finish.find(operation_colour(1)), std::string::npos) << finish;
  EXPECT_NE(finish.find("T5 ball 6"), std::string::npos);
  const std::string rest = row_of(html, "rest corners");
  EXPECT_NE(rest.find(operation_colour(2)), std::string::npos);
  EXPECT_NE(rest.find("nothing left to cut"), std::string::npos);
  const std::string bottom = row_of(html, "face bottom");
  EXPECT_NE(bottom.find(operation_colour(0)), std::string::npos) << "first of its setup";
  EXPECT_NE(bottom.find("47:26"), std::string::npos);
  EXPECT_NE(row_of(html, "Setup total").find("0:14:39"), std::string::npos);

  EXPECT_NE(html.find("finish &lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);

  // The pictures are the setups' own, 900 x 600; the first shows its three operations' colours as drawn.
  const auto pictures = inline_pictures(html);
  ASSERT_EQ(pictures.size(), 2u);
  const Picture first = decode(pictures[0]), second = decode(pictures[1]);
  EXPECT_EQ(first.width, 900);
  EXPECT_EQ(first.height, 600);
  EXPECT_EQ(second.width, 900);
  EXPECT_GT(count_colour(first, operation_colour(1)), 100u);
  EXPECT_EQ(count_colour(second, operation_colour(1)), 0u) << "the second setup has one operation";
  EXPECT_GT(count_colour(second, operation_colour(0)), 100u);
  EXPECT_EQ(pictures[0], setup_picture_png(s->part, s->report.setups[0].fixture, operations_of(*s, 0), 900, 600));
}

TEST(SetupSheet, TellsWhatNoSetupMachinesWhenSetupsWereChosen) {
  auto s = sample();
  EXPECT_EQ(setup_sheet_html(s->job).find("Not machined"), std::string::npos) << "no part area: not told";
  s->report.part_area = 21600;
  s->report.unreachable_area = 432;
  setups::Unreached u;
  u.reason = "hidden by the fixture";
  u.area = 432;
  u.centroid = Vec3(30, 0, 2.5);
  s->report.unreachable.push_back(u);
  const std::string html = setup_sheet_html(s->job);
  EXPECT_NE(html.find("Not machined by any setup"), std::string::npos);
  EXPECT_NE(html.find("432 mm&sup2; of the part's 21600 mm&sup2; (2 %)"), std::string::npos);
  const std::string row = row_of(html, "hidden by the fixture");
  EXPECT_NE(row.find(">432<"), std::string::npos) << row;
  EXPECT_NE(row.find("(30, 0, 2.5)"), std::string::npos) << row;
}

// Every tool by its T number, once each in order, and the faces the job left above their limit: where, how much,
// why; with none, the sheet says every face is within its limit.
TEST(SetupSheet, ListsTheToolsByNumberAndTheFacesLeftAboveTheirLimit) {
  auto s = sample();
  s->report.surface.done = true;
  s->report.surface.asked_faces = 6;
  s->report.surface.max_left_mm = 0.004;
  std::string html = setup_sheet_html(s->job);
  EXPECT_NE(html.find("6 faces to finish; every one within its limit"), std::string::npos);
  const size_t t3 = html.find(">T3<"), t5 = html.find(">T5<"), t7 = html.find(">T7<");
  ASSERT_NE(t3, std::string::npos);
  EXPECT_LT(t3, t5);
  EXPECT_LT(t5, t7);
  EXPECT_EQ(occurrences(html, ">T5<"), 1u);
  job::FaceLeft f;
  f.face = 12;
  f.setup = 1;
  f.verdict = job::FaceVerdict::Above;
  f.limit = 0.01;
  f.max_left_mm = 8.0;
  f.above_area = 180.5;
  f.most_at = Vec3(8, 15.5, 12);
  f.reason_area[static_cast<int>(job::LeftReason::ToolDoesNotFit)] = 180.5;
  s->report.surface.faces.push_back(f);
  s->report.surface.unfinished_faces = 1;
  s->report.surface.unfinished_area = 180.5;
  html = setup_sheet_html(s->job);
  EXPECT_NE(html.find("1 left above their limit over 180.5 mm&sup2; (the job is refused)"), std::string::npos);
  const std::string row = row_of(html, "tool does not fit");
  EXPECT_NE(row.find(">12<"), std::string::npos) << row;
  EXPECT_NE(row.find("2 bottom"), std::string::npos) << row;
  EXPECT_NE(row.find(">8<"), std::string::npos) << row;
  EXPECT_NE(row.find("(8, 15.5, 12)"), std::string::npos) << row;
}

TEST(SetupSheet, EscapesEveryTextFromTheJob) {
  auto s = sample();
  s->job.title = "a&b <job>.yaml";
  s->report.setups[0].name = "\"quoted\" setup";
  s->report.setups[0].fixture.description = "vise <b>big</b>";
  s->report.setups[0].fixture.boxes[0].name = "jaw's <i>";
  s->report.setups[0].program = "/out/<evil>&.ngc";
  s->report.operations[0].strategy = "<img src=x onerror=alert(1)>";
  s->report.part_area = 1;
  setups::Unreached u;
  u.reason = "<svg onload=alert(1)>";
  s->report.unreachable.push_back(u);
  const std::string html = setup_sheet_html(s->job);
  EXPECT_NE(html.find("a&amp;b &lt;job&gt;.yaml"), std::string::npos);
  EXPECT_NE(html.find("&quot;quoted&quot; setup"), std::string::npos);
  EXPECT_NE(html.find("vise &lt;b&gt;big&lt;/b&gt;"), std::string::npos);
  EXPECT_NE(html.find("jaw&#39;s &lt;i&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;evil&gt;&amp;.ngc"), std::string::npos);
  EXPECT_NE(html.find("&lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;svg onload=alert(1)&gt;"), std::string::npos);
  for (const char* raw : {"<job>", "<b>", "<i>", "<evil>", "<img src=x", "<svg", "\"quoted\""})
    EXPECT_EQ(html.find(raw), std::string::npos) << raw;
}

TEST(SetupSheet, RefusesAReportItCannotRead) {
  auto s = sample();
  s->job.report = nullptr;
  EXPECT_NE(error_of([&] { setup_sheet_html(s->job); }).find("no job report"), std::string::npos);
  s->job.report = &s->report;
  s->report.setups[1].operations.push_back(9);
  EXPECT_NE(error_of([&] { setup_sheet_html(s->job); }).find("setup 2 lists operation 10 of 4"), std::string::npos);
}

TEST(SetupSheet, WithoutToolpathsOrPartStillDrawsEverySetup) {
  auto s = sample();
  s->job.toolpaths.clear();  // a cancelled job, or a report read back without its toolpaths
  s->job.part = nullptr;
  const auto pictures = inline_pictures(setup_sheet_html(s->job));
  ASSERT_EQ(pictures.size(), 2u);
  const Picture p = decode(pictures[0]);
  EXPECT_GT(count(p, brown), 1000u) << "the fixture";
  EXPECT_EQ(count(p, grey_blue), 0u) << "no part";
}

TEST(SetupSheet, WritesTheFileOrSaysWhichItCannot) {
  const auto s = sample();
  const std::string path = (std::filesystem::temp_directory_path() / "rosmill_test_setup_sheet.html").string();
  write_setup_sheet(path, s->job);
  std::ifstream in(path, std::ios::binary);
  std::stringstream written;
  written << in.rdbuf();
  EXPECT_EQ(written.str(), setup_sheet_html(s->job));
  std::filesystem::remove(path);

  const std::string bad = "/nonexistent/dir/x.html";
  try {
    write_setup_sheet(bad, s->job);
    ADD_FAILURE() << "wrote " << bad;
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), bad);
    EXPECT_NE(std::string(e.what()).find("cannot open for writing"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(bad));
}
