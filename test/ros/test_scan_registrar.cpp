// rostest node for test/ros/scan_registrar.test. The test is the cell: it places the mount_rush relief on the
// table at a known pose, moves a sensor on tf between three views (the first at its true pose, the others' poses
// nudged 1 mm / 0.5 degrees off the truth, as a robot's repeatability would leave them), publishes what the sensor sees, and asks the node to fuse,
// register and inspect. Known answers: the fused cloud lies on the design within the noise; the workpiece frame
// on tf is the placed pose within 0.05 mm and 0.05 degrees; the bump of a re-scan is reported with its height and
// place; the bridge's program sets G54 to the registered pose.
#include <std_srvs/Trigger.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <thread>

#include "rosmill/InspectScan.h"
#include "rosmill/ProgramStatus.h"
#include "rosmill/RegisterScan.h"
#include "rosmill/SaveScan.h"
#include "rosmill/ToolpathJob.h"
#include "rosmill/gcode/post.hpp"
#include "rosmill/geometry/rigid_transform.hpp"
#include "rosmill/io/cloud_io.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/scan/mesh_distance.hpp"
#include "rosmill/testing/synthetic_scan.hpp"
#include "rostest_support.hpp"
#include "square_job.hpp"

using namespace rosmill;
using namespace rosmill::edge;
using rosmill::rostest::Latest;
using rosmill::rostest::call_service;
using rosmill::rostest::node_answers;
using rosmill::rostest::param;

namespace {

constexpr double kNoise = 0.02;  // mm

Eigen::Matrix4d pose(double rz_deg, double rx_deg, const Vec3& at_mm) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = (Eigen::AngleAxisd(rz_deg * M_PI / 180, Vec3::UnitZ()) *
                             Eigen::AngleAxisd(rx_deg * M_PI / 180, Vec3::UnitX()))
                                .toRotationMatrix();
  t.topRightCorner<3, 1>() = at_mm;
  return t;
}

// Where the test clamped the part: turned 25 degrees on the table and moved (table <- design, mm).
const Eigen::Matrix4d kPart = pose(25, 0, Vec3(120, -60, -30));

geometry_msgs::TransformStamped stamped(const Eigen::Matrix4d& t_mm, const std::string& parent,
                                        const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped m =
      to_transform_msg(parent, child, Eigen::Quaterniond(Eigen::Matrix3d(t_mm.topLeftCorner<3, 3>())).normalized(),
                       t_mm.topRightCorner<3, 1>() * kMetrePerMm);
  m.header.stamp = stamp;
  return m;
}

class Cell : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    design_ = new Mesh(read_stl(param("design")));
    for (const char* s : {"start", "add_view", "finish", "reset", "register", "inspect", "save"})
      ASSERT_TRUE(ros::service::waitForService(std::string("/scan_registrar/") + s, ros::Duration(30.0))) << s;
  }

  template <class Srv>
  Srv call(const std::string& name, Srv srv = Srv()) {
    EXPECT_TRUE(call_service("/scan_registrar/" + name, srv)) << name << ": the node is gone";
    return srv;
  }
  std_srvs::Trigger trigger(const std::string& name) { return call<std_srvs::Trigger>(name); }

  // add_view takes the first cloud after the call: the sensor publishes its pose and what it sees, stamped
  // alike, every 0.1 s until the call returns.
  std_srvs::Trigger add_view(const std::string& frame, const Eigen::Matrix4d* told_pose, const PointCloud& seen) {
    std::future<std_srvs::Trigger> reply = std::async(std::launch::async, [this] { return trigger("add_view"); });
    while (reply.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
      const ros::Time now = ros::Time::now();
      if (told_pose) tf_.sendTransform(stamped(*told_pose, "table", frame, now));
      sensor_msgs::PointCloud2 cloud = to_cloud_msg(seen, frame);
      cloud.header.stamp = now;
      views_.publish(cloud);
    }
    return reply.get();
  }

  static Mesh* design_;
  ros::NodeHandle nh;
  tf2_ros::TransformBroadcaster tf_;
  ros::Publisher views_ = nh.advertise<sensor_msgs::PointCloud2>("/scan_views", 2);
};
Mesh* Cell::design_ = nullptr;

}  // namespace

TEST_F(Cell, ThreeViewsFromAMovingSensorFuseWithinTheNoise) {
  ASSERT_TRUE(trigger("start").response.success);
  const std::vector<Vec3> sensors = synthetic::sensors_above(*design_, 2, 400);
  ASSERT_EQ(sensors.size(), 3u);
  for (size_t k = 0; k < sensors.size(); ++k) {
    // The sensor at its place over the part, looking down (table <- sensor). The first view is the reference
    // (a calibrated pose: fusion keeps it); tf is told the others' poses nudged by 1 mm and 0.5 degrees.
    const Eigen::Matrix4d truth = kPart * pose(40.0 * k, 180, sensors[k]);
    const Eigen::Matrix4d told =
        k == 0 ? truth : Eigen::Matrix4d(truth * synthetic::nudge(1.0, 0.5, Vec3(1, 2, 3 + k).normalized()));
    PointCloud seen;
    seen.points = transformed_points(rigid_inverse(truth) * kPart,
                                     synthetic::synthetic_scan(*design_, {sensors[k]}, 20000, kNoise, 11 + k).points);
    const std_srvs::Trigger r = add_view("sensor", &told, seen);
    ASSERT_TRUE(r.response.success) << r.response.message;
  }
  Latest<sensor_msgs::PointCloud2> fused(nh, "/fused_cloud");
  const std_srvs::Trigger r = trigger("finish");
  ASSERT_TRUE(r.response.success) << r.response.message;
  EXPECT_NE(r.response.message.find("3 views fused"), std::string::npos) << r.response.message;
  const auto msg = fused.wait(10.0);
  ASSERT_TRUE(msg);
  EXPECT_EQ(msg->header.frame_id, "table");
  const PointCloud cloud = from_cloud_msg(*msg);
  const scan::MeshDistance distance(*design_);
  const std::vector<double> d = distance.distances(transformed_points(rigid_inverse(kPart), cloud.points));
  double sum2 = 0;
  for (double x : d) sum2 += x * x;
  const double rms = std::sqrt(sum2 / double(d.size()));
  std::printf("fused: %zu points, RMS distance to the design %.4f mm (noise %.3f mm per axis)\n", d.size(), rms,
              kNoise);
  EXPECT_GT(d.size(), 20000u);
  EXPECT_LT(rms, 2.5 * kNoise) << "the fused cloud is off the design";  // 3-D noise of 0.02 per axis: ~0.035
}

TEST_F(Cell, TheFusedScanRegistersAndTheWorkpieceFrameIsPublished) {
  const RegisterScan r = call<RegisterScan>("register");
  ASSERT_TRUE(r.response.success) << r.response.message;
  EXPECT_FALSE(r.response.ambiguous);
  EXPECT_LT(r.response.rms, 0.05e-3);
  EXPECT_GT(r.response.inlier_share, 0.9);
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(buffer.canTransform("table", "workpiece", ros::Time(0), ros::Duration(10.0)));
  Eigen::Matrix4d found = tf2::transformToEigen(buffer.lookupTransform("table", "workpiece", ros::Time(0))).matrix();
  found.topRightCorner<3, 1>() *= kMmPerMetre;
  const Eigen::Matrix4d error = rigid_inverse(kPart) * found;
  std::printf("registered: %s; pose error %.4f mm, %.4f deg\n", r.response.message.c_str(),
              translation_length(error), rotation_angle_deg(error));
  EXPECT_LT(translation_length(error), 0.05);
  EXPECT_LT(rotation_angle_deg(error), 0.05);
  // The fused scan written in the workpiece frame (a job's stock): on the design where it stands.
  SaveScan save;
  save.request.path = "/tmp/rosmill_scan_registrar_fused.pcd";
  save = call("save", save);
  ASSERT_TRUE(save.response.success) << save.response.message;
  const PointCloud saved = read_cloud(save.request.path);
  ASSERT_EQ(saved.points.size(), save.response.points);
  const std::vector<double> d = scan::MeshDistance(*design_).distances(saved.points);
  double sum2 = 0;
  for (double x : d) sum2 += x * x;
  EXPECT_LT(std::sqrt(sum2 / double(d.size())), 2.5 * kNoise);
  save.request.path = "";
  EXPECT_FALSE(call("save", save).response.success);
}

TEST_F(Cell, BadViewsAndTheWrongPartAreRefusedAndNothingIsPublished) {
  ASSERT_TRUE(trigger("reset").response.success);
  const PointCloud some = synthetic::synthetic_scan(*design_, synthetic::sensors_above(*design_, 0, 400), 2000,
                                                    kNoise, 3);
  // No cloud comes.
  std_srvs::Trigger r = trigger("add_view");
  EXPECT_FALSE(r.response.success);
  EXPECT_NE(r.response.message.find("no cloud came on the scan topic within 2"), std::string::npos)
      << r.response.message;
  // A sensor frame tf never heard of.
  r = add_view("ghost_sensor", nullptr, some);
  EXPECT_FALSE(r.response.success);
  EXPECT_NE(r.response.message.find("no transform from 'ghost_sensor' to 'table' at its stamp"), std::string::npos)
      << r.response.message;
  // A NaN pose: tf refuses to store it, so the view has none.
  Eigen::Matrix4d nan_pose = pose(0, 180, Vec3(0, 0, 400));
  nan_pose(0, 3) = NAN;
  r = add_view("nan_sensor", &nan_pose, some);
  EXPECT_FALSE(r.response.success);
  EXPECT_NE(r.response.message.find("no transform from 'nan_sensor'"), std::string::npos) << r.response.message;
  // An empty view.
  const Eigen::Matrix4d above = pose(0, 180, Vec3(0, 0, 400));
  r = add_view("sensor", &above, PointCloud{});
  EXPECT_FALSE(r.response.success);
  EXPECT_NE(r.response.message.find("has no finite points"), std::string::npos) << r.response.message;
  // Nothing to fuse.
  r = trigger("finish");
  EXPECT_FALSE(r.response.success);
  EXPECT_NE(r.response.message.find("no views"), std::string::npos) << r.response.message;
  // The wrong part, seen straight in the table frame: refused, the workpiece frame stays where it was.
  const Mesh other = read_stl(param("other_part"));
  PointCloud wrong = synthetic::synthetic_scan(other, synthetic::sensors_above(other, 0, 400), 20000, kNoise, 5);
  const std::string table = "table";
  std::atomic<bool> done{false};
  std::thread sensor([&] {
    while (!done) {
      sensor_msgs::PointCloud2 m = to_cloud_msg(wrong, table);
      m.header.stamp = ros::Time::now();
      views_.publish(m);
      ros::WallDuration(0.1).sleep();
    }
  });
  ros::WallDuration(0.5).sleep();
  RegisterScan reg;
  reg.request.scan = "latest";
  reg = call("register", reg);
  done = true;
  sensor.join();
  EXPECT_FALSE(reg.response.success);
  EXPECT_FALSE(reg.response.message.empty());
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(buffer.canTransform("table", "workpiece", ros::Time(0), ros::Duration(10.0)));
  const Eigen::Vector3d at =
      tf2::transformToEigen(buffer.lookupTransform("table", "workpiece", ros::Time(0))).translation() * kMmPerMetre;
  EXPECT_LT((at - Vec3(kPart.topRightCorner<3, 1>())).norm(), 0.05) << "the refused fit moved the workpiece frame";
  EXPECT_TRUE(node_answers("/scan_registrar"));
}

TEST_F(Cell, ARescanWithABumpReportsItsHeightAndPlace) {
  // The machined part seen from above in the table frame, 0.5 mm of material left in a cap of radius 6 mm.
  std::vector<Vec3> points =
      synthetic::synthetic_scan(*design_, synthetic::sensors_above(*design_, 0, 400), 60000, 0.005, 21).points;
  const scan::MeshDistance distance(*design_);
  const Vec3 box_centre = 0.5 * (design_->bbox.min + design_->bbox.max);
  Vec3 at(0, 0, -1e9);
  for (const Vec3& p : points)  // the highest point near the box's centre: on the top surface
    if (std::hypot(p.x() - box_centre.x(), p.y() - box_centre.y()) < 1.0 && p.z() > at.z()) at = p;
  for (Vec3& p : points) {
    const double r = (p - at).norm();
    if (r < 6.0) p += design_->normals[distance.query(p).face] * 0.25 * (1 + std::cos(M_PI * r / 6.0));
  }
  PointCloud scan;
  scan.points = transformed_points(kPart, points);
  const std::string stock = "/tmp/rosmill_scan_registrar_stock.pcd";
  std::filesystem::remove(stock);
  std::atomic<bool> done{false};
  std::thread sensor([&] {
    while (!done) {
      sensor_msgs::PointCloud2 m = to_cloud_msg(scan, "table");
      m.header.stamp = ros::Time::now();
      views_.publish(m);
      ros::WallDuration(0.1).sleep();
    }
  });
  ros::WallDuration(0.5).sleep();
  Latest<visualization_msgs::MarkerArray> markers(nh, "/scan_deviation_markers");
  const size_t markers_before = markers.count();
  InspectScan srv;
  srv.request.scan = "latest";
  srv.request.use_workpiece_frame = true;
  srv.request.stock_out = stock;
  srv = call("inspect", srv);
  done = true;
  sensor.join();
  ASSERT_TRUE(srv.response.success) << srv.response.message;
  std::printf("inspected: largest excess %.4f mm, %.3f mm from the bump's top\n", srv.response.largest_excess * 1e3,
              (from_point_msg(srv.response.largest_excess_at) - at).norm());
  EXPECT_NEAR(srv.response.largest_excess, 0.5e-3, 0.03e-3);
  EXPECT_LT((from_point_msg(srv.response.largest_excess_at) - at).norm(), 1.0);
  EXPECT_GT(srv.response.above_tolerance, 0u);
  EXPECT_TRUE(std::filesystem::exists(stock));
  const auto view = markers.wait(10.0, markers_before);
  ASSERT_TRUE(view);
  bool points_marker = false;
  for (const auto& m : view->markers)
    points_marker = points_marker || (m.ns == "scan_deviation" && m.points.size() == m.colors.size() &&
                                      m.points.size() > 1000 && m.header.frame_id == "workpiece");
  EXPECT_TRUE(points_marker);
}

TEST_F(Cell, TheBridgeSetsTheWorkOffsetToTheRegisteredPose) {
  std::filesystem::create_directories("/tmp/rosmill_scan_registrar_test");
  ros::Publisher pub = nh.advertise<msg::ToolpathJob>("/toolpath", 1, true);
  pub.publish(rosmill::rostest::square_job());
  ASSERT_TRUE(ros::service::waitForService("/gcode_bridge/start", ros::Duration(30.0)));
  std_srvs::Trigger start;
  // Until the bridge has the latched job; a call that fails on the way (seen once under load) is tried again.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(20.0);
  bool answered = false;
  do {
    answered = call_service("/gcode_bridge/start", start);
    if (answered && start.response.message.find("no job received") == std::string::npos) break;
    ros::WallDuration(0.05).sleep();
  } while (ros::WallTime::now() < end);
  ASSERT_TRUE(answered) << "the bridge's start service did not answer within 20 s";
  ASSERT_TRUE(start.response.success) << start.response.message;
  Latest<msg::ProgramStatus> status(nh, "/program_status");
  const auto s = status.wait(10.0);
  ASSERT_TRUE(s);
  std::string g10;
  for (const std::string& l : gcode::read_program_lines(s->program))
    if (l.rfind("G10 L2 P1", 0) == 0) g10 = l;
  ASSERT_FALSE(g10.empty()) << "no work offset in " << s->program;
  double x, y, z, r;
  ASSERT_EQ(std::sscanf(g10.c_str(), "G10 L2 P1 X%lf Y%lf Z%lf R%lf", &x, &y, &z, &r), 4) << g10;
  EXPECT_LT((Vec3(x, y, z) - Vec3(kPart.topRightCorner<3, 1>())).norm(), 0.06) << g10;
  EXPECT_NEAR(r, 25.0, 0.05) << g10;
}

int main(int argc, char** argv) { return rosmill::rostest::run_all(argc, argv, "test_scan_registrar"); }
