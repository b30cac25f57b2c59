// rostest node for test/ros/pipeline.test: the mesh pipeline on the seed dome (r 50 mm, 900 facets).
#include <algorithm>
#include <shape_msgs/Mesh.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <iostream>
#include <set>

#include "gouge_check.hpp"
#include "rosmill/LoadMesh.h"
#include "rosmill/Plan.h"
#include "rosmill/Segmentation.h"
#include "rosmill/SetSetup.h"
#include "rosmill/Slices.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/geometry/primitives.hpp"
#include "rosmill/ros/markers.hpp"
#include "rostest_support.hpp"

#include <diagnostic_msgs/DiagnosticArray.h>

#include <map>
#include <mutex>
#include <sys/stat.h>
#include <unistd.h>

using namespace rosmill;
using namespace rosmill::edge;
using rosmill::rostest::Latest;
using rosmill::rostest::call_service;
using rosmill::rostest::node_answers;

namespace {

constexpr double kRadius = 0.050;  // m
constexpr double kGougeTolerance = 0.02;  // mm: the planner's tolerance (at most 0.01) and the sampling of the check

void expect_all_nodes_up() {
  for (const char* node : {"/stl_loader", "/segmenter", "/slicer", "/toolpath_planner"})
    EXPECT_TRUE(node_answers(node)) << node << " does not answer";
}

class Pipeline : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_TRUE(ros::service::waitForService("load_mesh", ros::Duration(20.0)));
    ASSERT_TRUE(ros::service::waitForService("set_setup", ros::Duration(20.0)));
    ASSERT_TRUE(ros::service::waitForService("plan", ros::Duration(20.0)));
  }
  ros::NodeHandle nh;
};

// Whether each facet lies in a patch the setup can machine.
std::vector<bool> reachable_facets(const msg::Segmentation& s) {
  std::vector<bool> r(s.facet_labels.size());
  for (size_t f = 0; f < r.size(); ++f) r[f] = s.patches.at(s.facet_labels[f]).reachable;
  return r;
}

// The facet of the dome whose centroid is most along `d`.
size_t extreme_facet(const Mesh& mesh, const Vec3& d) {
  size_t best = 0;
  double best_value = -1e300;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const double v = (mesh.corner(f, 0) + mesh.corner(f, 1) + mesh.corner(f, 2)).dot(d);
    if (v > best_value) best_value = v, best = f;
  }
  return best;
}

SetSetup set_setup(const std::string& name, const Vec3& direction = Vec3::Zero(), double max_angle = 0.0) {
  SetSetup srv;
  srv.request.setup = name;
  srv.request.direction = edge::to_direction_msg(direction);
  srv.request.max_angle = max_angle;
  EXPECT_TRUE(call_service("set_setup", srv)) << "the segmenter is gone";
  return srv;
}

TEST_F(Pipeline, MeshIsPublishedInMetres) {
  Latest<shape_msgs::Mesh> mesh(nh, "mesh");
  auto m = mesh.wait(20.0);
  ASSERT_TRUE(m) << "no mesh from stl_loader";
  EXPECT_EQ(m->triangles.size(), 900u);
  for (const auto& v : m->vertices) EXPECT_LE(std::hypot(v.x, v.y, v.z), kRadius + 1e-9);
  Latest<visualization_msgs::Marker> marker(nh, "mesh_marker");
  auto mk = marker.wait(5.0);
  ASSERT_TRUE(mk);
  EXPECT_EQ(mk->type, visualization_msgs::Marker::TRIANGLE_LIST);
  EXPECT_EQ(mk->points.size(), 900u * 3);
}

// +Z and -X see different faces of the dome: the bottom disc only from the side, the +X flank only from above.
TEST_F(Pipeline, SegmentationsOfPlusZAndMinusXDiffer) {
  const Mesh dome = make_primitive("dome");
  Latest<msg::Segmentation> seg(nh, "segmentation");
  auto z = seg.wait(20.0);
  ASSERT_TRUE(z) << "no segmentation";
  EXPECT_EQ(z->setup, "+Z");
  ASSERT_EQ(z->facet_labels.size(), 900u);
  size_t facets = 0;
  double area = 0;
  for (size_t i = 0; i < z->patches.size(); ++i) {
    EXPECT_EQ(z->patches[i].label, i);
    facets += z->patches[i].facet_count;
    area += z->patches[i].area;
  }
  EXPECT_EQ(facets, 900u);
  EXPECT_NEAR(area, 3 * M_PI * kRadius * kRadius, 0.02 * 3 * M_PI * kRadius * kRadius);  // faceted: a bit less
  for (uint32_t label : z->facet_labels) EXPECT_LT(label, z->patches.size());
  EXPECT_NEAR(z->reachable_fraction, 2.0 / 3.0, 0.03);  // the hemisphere, not the bottom

  const size_t count = seg.count();
  SetSetup srv = set_setup("-X");
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  auto x = seg.wait(10.0, count);
  ASSERT_TRUE(x) << "no segmentation after set_setup";
  EXPECT_EQ(x->setup, "-X");
  EXPECT_NEAR(x->tool_axis.x, -1.0, 1e-12);
  EXPECT_EQ(srv.response.patches, x->patches.size());

  const std::vector<bool> rz = reachable_facets(*z), rx = reachable_facets(*x);
  const size_t bottom = extreme_facet(dome, -Vec3::UnitZ()), flank = extreme_facet(dome, Vec3(1, 0, 0.05));
  EXPECT_FALSE(rz[bottom]);
  EXPECT_TRUE(rx[bottom]);
  EXPECT_TRUE(rz[flank]);
  EXPECT_FALSE(rx[flank]);
  EXPECT_NE(rz, rx);

  SetSetup five = set_setup("5axis");
  ASSERT_TRUE(five.response.success) << five.response.message;
  EXPECT_NEAR(five.response.reachable_fraction, 1.0, 1e-9);
  SetSetup back = set_setup("+z");
  ASSERT_TRUE(back.response.success);
  EXPECT_NEAR(back.response.reachable_fraction, z->reachable_fraction, 1e-12);

  Latest<visualization_msgs::MarkerArray> markers(nh, "segmentation_markers");
  auto mk = markers.wait(5.0);
  ASSERT_TRUE(mk);
  ASSERT_GE(mk->markers.size(), 2u);
  EXPECT_EQ(mk->markers[0].action, visualization_msgs::Marker::DELETEALL);
  size_t triangles = 0;
  for (size_t i = 1; i < mk->markers.size(); ++i) {
    EXPECT_EQ(mk->markers[i].type, visualization_msgs::Marker::TRIANGLE_LIST);
    EXPECT_TRUE(mk->markers[i].ns == "reachable" || mk->markers[i].ns == "unreachable");
    triangles += mk->markers[i].points.size() / 3;
  }
  EXPECT_EQ(triangles, 900u);
}

// set_setup "auto": the setups chosen for the dome (its bottom disc needs -Z; the 6 mm ball's 28 mm holder keeps
// it from the dome's lowest belt from above), every facet coloured by the setup that machines it, and what they
// machine and leave adding up to the dome's area.
TEST_F(Pipeline, SetupsChosenForTheDome) {
  Latest<visualization_msgs::MarkerArray> markers(nh, "segmentation_markers");
  const size_t before = markers.count();
  SetSetup chosen = set_setup("auto");
  ASSERT_TRUE(chosen.response.success) << chosen.response.message;
  ASSERT_GE(chosen.response.setups.size(), 2u);
  EXPECT_EQ(chosen.response.setups.size(), chosen.response.setup_directions.size());
  EXPECT_EQ(chosen.response.setups.front(), "+Z");
  EXPECT_NE(std::find(chosen.response.setups.begin(), chosen.response.setups.end(), "-Z"), chosen.response.setups.end());
  double machined = chosen.response.unreachable_area;
  for (double a : chosen.response.setup_areas) machined += a;
  const double r = kRadius;
  EXPECT_NEAR(machined, 3 * M_PI * r * r, 0.02 * 3 * M_PI * r * r);
  // The markers of "auto": an array published for an earlier request may still arrive after `before` was read.
  bool by_setup = false;
  size_t seen = before;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  while (!by_setup && ros::WallTime::now() < end) {
    const auto mk = markers.wait((end - ros::WallTime::now()).toSec(), seen);
    if (!mk) break;
    seen = markers.count();
    for (const auto& m : mk->markers)
      if (m.ns == "setups") {
        by_setup = true;
        EXPECT_EQ(m.points.size(), 900u * 3);
        EXPECT_EQ(m.colors.size(), m.points.size());
      }
  }
  EXPECT_TRUE(by_setup);
  ASSERT_TRUE(set_setup("+Z").response.success);  // the segmentation the other tests expect
}

TEST_F(Pipeline, InvalidSetupsAreRefused) {
  SetSetup bad = set_setup("sideways");
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("sideways"), std::string::npos) << bad.response.message;
  SetSetup zero = set_setup("", Vec3::Zero());
  EXPECT_FALSE(zero.response.success);
  EXPECT_NE(zero.response.message.find("direction"), std::string::npos) << zero.response.message;
  SetSetup angle = set_setup("+Z", Vec3::Zero(), -1.0);
  EXPECT_FALSE(angle.response.success);
  EXPECT_NE(angle.response.message.find("angle"), std::string::npos) << angle.response.message;
  // Sent in radians, reported in radians and named as the request's field.
  SetSetup huge = set_setup("+Z", Vec3::Zero(), 1e9);
  EXPECT_FALSE(huge.response.success);
  EXPECT_EQ(huge.response.message.rfind("max_angle: ", 0), 0u) << huge.response.message;
  EXPECT_NE(huge.response.message.find("got 1000000000.000000 rad"), std::string::npos) << huge.response.message;
  SetSetup tilted = set_setup("", Vec3(1, 0, 1));  // a valid custom direction
  EXPECT_TRUE(tilted.response.success) << tilted.response.message;
  expect_all_nodes_up();
}

TEST_F(Pipeline, SlicesAreClosedCirclesOfTheDome) {
  Latest<msg::Slices> slices(nh, "slices");
  auto s = slices.wait(20.0);
  ASSERT_TRUE(s) << "no slices";
  EXPECT_NEAR(s->interval, 0.002, 1e-12);
  ASSERT_EQ(s->layers.size(), 25u);  // every 2 mm from z = 0 to the top at 50 mm
  EXPECT_EQ(s->open_contours, 0u);
  for (size_t k = 0; k + 1 < s->layers.size(); ++k) {  // the top plane touches only the apex
    const auto& layer = s->layers[k];
    EXPECT_NEAR(layer.z, 0.002 * (k + 1), 1e-9);
    ASSERT_EQ(layer.contours.size(), 1u) << "layer " << k;
    const auto& c = layer.contours[0];
    EXPECT_TRUE(c.closed);
    EXPECT_FALSE(c.hole);
    EXPECT_EQ(c.parent, -1);
    const double r = std::sqrt(kRadius * kRadius - layer.z * layer.z);
    // The section of a faceted sphere is a polygon inside the circle: its area within 5 % (36 sides at the foot,
    // fewer near the top) and never above the circle's.
    EXPECT_LE(c.area, M_PI * r * r);
    EXPECT_GT(c.area, 0.95 * M_PI * r * r) << "layer " << k;
    for (const auto& p : c.points) {
      EXPECT_DOUBLE_EQ(p.z, layer.z);
      EXPECT_LE(std::hypot(p.x, p.y, p.z), kRadius + 1e-9);
      EXPECT_GE(std::hypot(p.x, p.y, p.z), 0.049);  // the facets lie within 1 mm of the sphere
    }
  }
  Latest<visualization_msgs::MarkerArray> markers(nh, "slice_markers");
  auto mk = markers.wait(5.0);
  ASSERT_TRUE(mk);
  EXPECT_GE(mk->markers.size(), 25u);
  for (size_t i = 1; i < mk->markers.size(); ++i) EXPECT_EQ(mk->markers[i].type, visualization_msgs::Marker::LINE_LIST);
}

void expect_within_reach(const msg::Toolpath& tp, const Mesh& part_in_setup) {
  const double r = edge::to_mm(tp.tool.diameter) / 2, margin = 5.0;  // planner/stock_margin
  const Box3& box = part_in_setup.bbox;
  for (const auto& pass : tp.passes)
    for (const auto& move : pass.moves) {
      const Vec3 p = edge::from_point_msg(move.position);
      EXPECT_GE(p.x(), box.min.x() - margin - r - 1e-6);
      EXPECT_LE(p.x(), box.max.x() + margin + r + 1e-6);
      EXPECT_GE(p.y(), box.min.y() - margin - r - 1e-6);
      EXPECT_LE(p.y(), box.max.y() + margin + r + 1e-6);
      EXPECT_GE(p.z(), box.min.z() - 1e-6) << "below the part in pass " << pass.name;
      EXPECT_LE(p.z(), edge::to_mm(tp.clearance_z) + 1e-6);
    }
}

size_t move_count(const msg::Toolpath& tp) {
  size_t n = 0;
  for (const auto& pass : tp.passes) n += pass.moves.size();
  return n;
}

// The toolpath the planner published for the dome (+Z, raster, 6 mm ball) and the one for -X: each within reach
// of the part and free of gouges against the part's own facets in its setup frame, and different from each other.
TEST_F(Pipeline, ToolpathsForPlusZAndMinusXDoNotGouge) {
  const Mesh dome = make_primitive("dome");
  Latest<msg::ToolpathJob> job(nh, "toolpath");
  auto z = job.wait(30.0);
  ASSERT_TRUE(z) << "no toolpath";
  ASSERT_EQ(z->toolpaths.size(), 1u);
  const msg::Toolpath& tz = z->toolpaths[0];
  EXPECT_EQ(tz.setup, "+Z");
  EXPECT_EQ(tz.strategy, "raster");
  EXPECT_EQ(tz.tool.cutter_type, msg::Tool::BALL_END);
  EXPECT_NEAR(tz.tool.diameter, 0.006, 1e-12);
  EXPECT_GT(move_count(tz), 200u);
  expect_within_reach(tz, dome);
  const rostest::Gouge gz = rostest::ball_gouge(dome, tz);
  EXPECT_LE(gz.depth, kGougeTolerance) << "+Z gouges " << gz.depth << " mm at " << gz.at.transpose();
  EXPECT_GT(gz.samples, 1000u);
  std::cout << "+Z raster: deepest approach " << gz.depth << " mm over " << gz.samples << " cutter positions\n";
  // The check itself: the same toolpath 0.5 mm lower must be caught (about 0.5 mm deep on the dome's top).
  msg::Toolpath lowered = tz;
  for (auto& pass : lowered.passes)
    for (auto& move : pass.moves) move.position.z -= 0.0005;
  EXPECT_NEAR(rostest::ball_gouge(dome, lowered).depth, 0.5, 0.05);

  Plan srv;
  srv.request.setup = "-X";
  srv.request.source = "mesh";
  const size_t count = job.count();
  ASSERT_TRUE(call_service("plan", srv));
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  auto x = job.wait(10.0, count);
  ASSERT_TRUE(x);
  const msg::Toolpath& tx = x->toolpaths.at(0);
  EXPECT_EQ(tx.setup, "-X");
  EXPECT_EQ(srv.response.statistics.moves, move_count(tx));
  // The positions are in the setup frame: the dome turned so that -X points up.
  SetupFrame setup;
  setup.placement = placement_of("setup -X", kWorkpieceFrame,
                                 Eigen::Quaterniond(tx.setup_rotation.w, tx.setup_rotation.x, tx.setup_rotation.y,
                                                    tx.setup_rotation.z),
                                 edge::from_vector_msg(tx.setup_translation));
  EXPECT_NEAR((setup.direction_to_setup(Vec3(-1, 0, 0)) - Vec3::UnitZ()).norm(), 0.0, 1e-9);
  const Mesh turned = placed(dome, setup.placement);
  expect_within_reach(tx, turned);
  const rostest::Gouge gx = rostest::ball_gouge(turned, tx);
  EXPECT_LE(gx.depth, kGougeTolerance) << "-X gouges " << gx.depth << " mm at " << gx.at.transpose();
  std::cout << "-X raster: deepest approach " << gx.depth << " mm over " << gx.samples << " cutter positions\n";
  EXPECT_NE(move_count(tx), move_count(tz));
  // From above the dome is 50 mm tall; turned on its side it is 100 mm tall: the cutter goes down much further.
  const auto& bx = srv.response.statistics;
  EXPECT_LT(bx.bounds_min.z, -0.020);
}

// The view: a DELETEALL, one LINE_STRIP per pass in its own namespace, colours of the three move types only, and
// the tool at the start.
TEST_F(Pipeline, ToolpathMarkersShowPassesMoveTypesAndTool) {
  Latest<visualization_msgs::MarkerArray> markers(nh, "toolpath_markers");
  auto mk = markers.wait(10.0);
  ASSERT_TRUE(mk);
  ASSERT_GE(mk->markers.size(), 3u);
  EXPECT_EQ(mk->markers[0].action, visualization_msgs::Marker::DELETEALL);
  std::set<std::string> namespaces;
  size_t strips = 0, tools = 0;
  const std::vector<std_msgs::ColorRGBA> colours = {edge::move_colour(MoveType::Rapid), edge::move_colour(MoveType::Feed),
                                                    edge::move_colour(MoveType::Plunge)};
  std::set<int> used;
  for (size_t i = 1; i < mk->markers.size(); ++i) {
    const auto& m = mk->markers[i];
    EXPECT_TRUE(namespaces.insert(m.ns).second) << "namespace " << m.ns << " twice";
    if (m.type == visualization_msgs::Marker::LINE_STRIP) {
      ++strips;
      ASSERT_EQ(m.colors.size(), m.points.size());
      for (const auto& c : m.colors) {
        int found = -1;
        for (size_t k = 0; k < colours.size(); ++k)
          if (c.r == colours[k].r && c.g == colours[k].g && c.b == colours[k].b) found = int(k);
        EXPECT_GE(found, 0) << "a colour that is no move type";
        used.insert(found);
      }
    } else if (m.type == visualization_msgs::Marker::CYLINDER) {
      ++tools;
      EXPECT_NEAR(m.scale.x, 0.006, 1e-12);
    }
  }
  EXPECT_GE(strips, 1u);
  EXPECT_EQ(tools, 1u);
  EXPECT_TRUE(used.count(0) && used.count(1)) << "rapids and feeds are both drawn";
}

// Asks stl_loader for a load that must be refused at once, with `expect` in the reason.
void expect_refused_load(const std::string& path, const std::string& expect, const std::string& units = "",
                         const std::string& frame_id = "") {
  LoadMesh load;
  load.request.path = path;
  load.request.units = units;
  load.request.frame_id = frame_id;
  const ros::WallTime t0 = ros::WallTime::now();
  ASSERT_TRUE(call_service("load_mesh", load)) << "stl_loader is gone";
  EXPECT_FALSE(load.response.success) << path;
  EXPECT_NE(load.response.message.find(expect), std::string::npos) << load.response.message;
  EXPECT_LT((ros::WallTime::now() - t0).toSec(), 10.0) << path << " was not refused at once";
}

TEST_F(Pipeline, BadLoadsAreRefusedAndTheNodesStayUp) {
  expect_refused_load("/no/such/part.stl", "/no/such/part.stl");
  expect_refused_load("primitive:cube", "furlong", "furlong");
  expect_refused_load("primitive:teapot", "teapot");
  // Not an STL at all: a point cloud file.
  std::string data;
  ASSERT_TRUE(ros::param::get("~data", data));
  expect_refused_load(data + "/pcl_bunny.pcd", "pcl_bunny.pcd");
  // Not files: a device and a FIFO would be read until memory runs out; they are refused at once.
  const std::string fifo = "/tmp/rosmill-pipeline-fifo-" + std::to_string(::getpid());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_refused_load("/dev/zero", "not a regular file");
  expect_refused_load(fifo, "not a regular file");
  ::unlink(fifo.c_str());
  // A part in a frame tf does not know is refused: publishing it in the workpiece frame would put it elsewhere.
  expect_refused_load("primitive:cube", "no transform to 'workpiece'", "", "nowhere");
  expect_all_nodes_up();
}

// Every node of the pipeline (and the static frame) reports on /diagnostics what it did with its last input; the
// loader's refusal of a bad path names the path.
TEST_F(Pipeline, EveryNodeReportsItsLastInput) {
  std::map<std::string, std::string> heard;  // status name -> message
  std::mutex m;
  ros::Subscriber sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 50, boost::function<void(const diagnostic_msgs::DiagnosticArray::ConstPtr&)>(
                              [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& a) {
                                std::lock_guard<std::mutex> lock(m);
                                for (const auto& st : a->status) heard[st.name] = st.message;
                              }));
  expect_refused_load("/no/such/diagnosed.stl", "no such file");
  const std::vector<std::string> names = {"stl_loader: input", "segmenter: input", "slicer: input",
                                          "toolpath_planner: input", "fixture_frame: input"};
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  auto all_heard = [&] {
    std::lock_guard<std::mutex> lock(m);
    for (const std::string& n : names)
      if (!heard.count(n)) return false;
    return heard["stl_loader: input"].find("diagnosed.stl") != std::string::npos;
  };
  while (!all_heard() && ros::WallTime::now() < end) ros::WallDuration(0.05).sleep();
  std::lock_guard<std::mutex> lock(m);
  for (const std::string& n : names) EXPECT_TRUE(heard.count(n)) << n << " published no diagnostic";
  EXPECT_NE(heard["stl_loader: input"].find("rejected"), std::string::npos) << heard["stl_loader: input"];
  EXPECT_NE(heard["stl_loader: input"].find("diagnosed.stl"), std::string::npos) << heard["stl_loader: input"];
  EXPECT_NE(heard["fixture_frame: input"].find("fixture published in workpiece"), std::string::npos);
}

// A real model through the whole chain: every node takes the new mesh.
TEST_F(Pipeline, ARealModelReachesEveryNode) {
  Latest<msg::Segmentation> seg(nh, "segmentation");
  Latest<msg::Slices> slices(nh, "slices");
  Latest<msg::ToolpathJob> job(nh, "toolpath");
  ASSERT_TRUE(seg.wait(5.0) && slices.wait(5.0) && job.wait(5.0));
  const size_t s0 = seg.count(), l0 = slices.count(), j0 = job.count();
  std::string data;
  ASSERT_TRUE(ros::param::get("~data", data));
  LoadMesh load;
  load.request.path = data + "/failedinpycam.stl";
  ASSERT_TRUE(call_service("load_mesh", load));
  ASSERT_TRUE(load.response.success) << load.response.message;
  EXPECT_EQ(load.response.triangles, 428u);
  auto s = seg.wait(20.0, s0);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->facet_labels.size(), 428u);
  auto l = slices.wait(20.0, l0);
  ASSERT_TRUE(l);
  EXPECT_GT(l->layers.size(), 0u);
  auto j = job.wait(30.0, j0);
  ASSERT_TRUE(j);
  ASSERT_EQ(j->toolpaths.size(), 1u);
  for (const auto& pass : j->toolpaths[0].passes)
    for (const auto& move : pass.moves) {
      EXPECT_GE(move.position.z, load.response.bounds_min.z - 1e-9);
      EXPECT_LE(move.position.z, j->toolpaths[0].clearance_z + 1e-9);
    }
  expect_all_nodes_up();
}

// A part given in another frame (the fixture, 10 mm along x from the workpiece origin in pipeline.test) is moved
// into the workpiece frame before it is published: the toolpath that every node downstream plans is where the
// part is, not where its file's numbers say.
TEST_F(Pipeline, APartInAnotherFrameIsPlacedWhereItIs) {
  Latest<msg::ToolpathJob> job(nh, "toolpath");
  ASSERT_TRUE(job.wait(5.0));
  const size_t j0 = job.count();
  LoadMesh plain, moved;
  plain.request.path = moved.request.path = "primitive:cube";
  moved.request.frame_id = "fixture";
  ASSERT_TRUE(call_service("load_mesh", plain));
  ASSERT_TRUE(plain.response.success) << plain.response.message;
  ASSERT_TRUE(call_service("load_mesh", moved));
  ASSERT_TRUE(moved.response.success) << moved.response.message;
  EXPECT_NEAR(moved.response.bounds_min.x - plain.response.bounds_min.x, 0.010, 1e-9);
  EXPECT_NEAR(moved.response.bounds_max.x - plain.response.bounds_max.x, 0.010, 1e-9);
  EXPECT_NEAR(moved.response.bounds_min.y, plain.response.bounds_min.y, 1e-9);
  // The plan of the plain cube may come first (or be superseded): wait for the one centred on the moved cube.
  auto centre_x = [](const msg::ToolpathJob& m) {
    double lo = 1e9, hi = -1e9;
    for (const auto& tp : m.toolpaths)
      for (const auto& pass : tp.passes)
        for (const auto& move : pass.moves)
          if (move.move_type != msg::ToolpathMove::RAPID) lo = std::min(lo, move.position.x), hi = std::max(hi, move.position.x);
    return (lo + hi) / 2;
  };
  boost::shared_ptr<const msg::ToolpathJob> j;
  const double cube_x = (moved.response.bounds_min.x + moved.response.bounds_max.x) / 2;
  for (size_t seen = j0; (j = job.wait(30.0, seen)) && std::abs(centre_x(*j) - cube_x) > 1e-3;) seen = job.count();
  ASSERT_TRUE(j) << "no toolpath centred on the cube where the fixture holds it";
  EXPECT_EQ(j->header.frame_id, "workpiece");
  expect_all_nodes_up();
}

}  // namespace

int main(int argc, char** argv) { return rosmill::rostest::run_all(argc, argv, "test_pipeline"); }
