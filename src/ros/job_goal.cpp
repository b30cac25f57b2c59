#include "rosmill/ros/job_goal.hpp"

#include <ros/ros.h>

#include <chrono>
#include <cmath>
#include <filesystem>

#include "rosmill/error.hpp"
#include "rosmill/job/job_progress.hpp"
#include "rosmill/job/job_spec.hpp"
#include "rosmill/number_text.hpp"
#include "rosmill/ros/convert.hpp"
#include "rosmill/ros/finish_goal.hpp"
#include "rosmill/ros/job_markers.hpp"
#include "rosmill/ros/params.hpp"
#include "rosmill/sheet/setup_sheet.hpp"

namespace rosmill::edge {
namespace {

constexpr double kMm3ToM3 = 1e-9;

job::JobSpec goal_job(const PlanJobGoal& goal) {
  if (!goal.job_file.empty()) return job::read_job(goal.job_file);
  if (goal.job_yaml.empty()) throw Error("goal", "names no job: give job_file (a path) or job_yaml (the text)");
  const std::string folder = goal.folder.empty() ? std::filesystem::current_path().string() : goal.folder;
  return job::parse_job(goal.job_yaml, "goal job_yaml", folder);
}

msg::JobOperationReport to_operation_msg(const job::OperationReport& r) {
  msg::JobOperationReport m;
  m.name = r.name;
  m.strategy = r.strategy;
  m.tool = r.tool;
  m.setup = r.setup;
  m.setup_index = static_cast<uint32_t>(r.setup_index);
  m.moves = static_cast<uint32_t>(r.moves);
  m.cutting_length = to_metres(r.cutting_mm);
  m.rapid_length = to_metres(r.rapid_mm);
  m.air_cut_share = r.air_cut_share;
  m.removed_volume = r.removed_mm3 * kMm3ToM3;
  m.time = r.time_s;
  m.planning_time = r.plan_seconds;
  m.min_left = to_metres(r.min_left_mm);
  m.max_left = to_metres(r.max_left_mm);
  m.program = r.program;
  return m;
}

msg::JobSetup to_setup_msg(const job::SetupReport& s, const std::string& frame_id) {
  msg::JobSetup m;
  m.name = s.name;
  m.frame_id = frame_id;
  m.tool_axis = to_direction_msg(s.direction);
  m.source = s.source;
  m.face_down = s.face_down;
  m.fixture = s.fixture.description;
  m.datum = job::datum_name(s.datum);
  m.datum_point = to_point_msg(s.datum_point);
  m.work_offset = s.work_offset ? s.work_offset->code() : "G54";
  m.work_offset_set = s.work_offset.has_value();
  if (s.work_offset) m.work_offset_origin = to_point_msg(s.work_offset->origin);
  for (size_t k : s.operations) m.operations.push_back(static_cast<uint32_t>(k));
  m.finished_area = s.finished_area * kMetrePerMm * kMetrePerMm;
  m.time = s.time_s;
  m.program = s.program;
  m.indexed = s.index.has_value();
  if (s.index) {
    m.a = to_radians(s.index->a);
    m.c = to_radians(s.index->c);
    m.indexing_time = s.indexing_s;
  }
  return m;
}

}  // namespace

PlanJobResult to_job_result(const job::JobReport& report) {
  PlanJobResult result;
  for (const job::OperationReport& r : report.operations) result.operations.push_back(to_operation_msg(r));
  result.unreachable_area = report.unreachable_area * kMetrePerMm * kMetrePerMm;
  result.cancelled = report.cancelled;
  result.stock_volume = report.stock_mm3 * kMm3ToM3;
  result.left_volume = report.left_mm3 * kMm3ToM3;
  result.air_cut_share = report.air_cut_share;
  result.time = report.time_s;
  result.min_left = to_metres(report.operations.empty() ? 0.0 : report.min_left_mm);
  result.max_left = to_metres(report.max_left_mm);
  result.faces_to_finish = static_cast<uint32_t>(report.surface.asked_faces);
  result.unfinished_faces = static_cast<uint32_t>(report.surface.unfinished_faces);
  result.unfinished_area = report.surface.unfinished_area * kMetrePerMm * kMetrePerMm;
  result.accept_unfinished = report.accept_unfinished;
  result.report_json = job::to_json(report).dump();
  return result;
}

PlanJobResult run_job_goal(const PlanJobGoal& goal, const JobGoalContext& context, bool& cancelled) {
  cancelled = false;
  PlanJobResult result;
  try {
    job::JobSpec spec = goal_job(goal);
    std::shared_ptr<const Mesh> received;
    if (goal.part_source == "mesh")
      received = context.received_mesh();
    else if (!goal.part_source.empty())
      throw Error("part_source", "must be \"\" (the job's part) or \"mesh\", got \"" + goal.part_source + "\"");
    if (!goal.output_dir.empty() && goal.output_dir.front() != '/')
      throw Error("output_dir", "must be an absolute folder, got '" + goal.output_dir + "'");
    job::JobRequest request = context.request;
    request.out_dir = goal.output_dir;
    request.per_operation = goal.per_operation;
    request.table_feeds = goal.table_feeds;
    request.part = received.get();
    request.work_offset = context.work_offset;
    job::JobOptions options = job::job_options(request);
    std::vector<Job> planned;  // each operation's toolpaths, for the programs and the setup sheet
    std::vector<std::string> frames;  // each setup's frame on tf
    options.operation_done = [&](const job::OperationView& view) {
      planned.push_back(view.toolpaths);
      if (view.report.setup_index == frames.size()) {
        frames.push_back(context.setup_frame(view.setup.frame, view.report.setup_index));
      }
      if (context.show) context.show(view);
    };
    auto last = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    size_t operations = spec.operations.size();
    job::report_progress(options, spec, [&](const job::JobProgress& p) {
      operations = p.operations;
      if (context.cancel_requested()) return false;
      const auto now = std::chrono::steady_clock::now();
      if (p.operation_fraction > 0 && p.operation_fraction < 1 && now - last < std::chrono::milliseconds(100))
        return true;
      last = now;
      PlanJobFeedback fb;
      fb.operation = static_cast<uint32_t>(p.operation);
      fb.operations = static_cast<uint32_t>(p.operations);
      fb.name = p.name;
      fb.stage = p.operation_fraction >= 1 ? "done" : "running";
      fb.operation_progress = static_cast<float>(p.operation_fraction);
      fb.progress = static_cast<float>(p.fraction);
      context.feedback(fb);
      return true;
    });
    const job::JobReport report = job::run_job(spec, options);
    result = to_job_result(report);
    if (context.show_surface && report.surface.done)
      context.show_surface(received ? *received : job::read_part(spec), report.surface);
    for (size_t k = 0; k < report.setups.size() && k < frames.size(); ++k)
      result.setups.push_back(to_setup_msg(report.setups[k], frames[k]));
    for (const auto& [first, end] : job::program_groups(report, goal.per_operation)) {
      Job toolpaths;
      for (size_t k = first; k < end; ++k) toolpaths.insert(toolpaths.end(), planned[k].begin(), planned[k].end());
      const size_t index = report.operations[first].setup_index;
      const job::SetupReport& setup = report.setups[index];
      std_msgs::Header header;
      header.frame_id = frames[index];
      header.stamp = ::ros::Time::now();
      msg::ToolpathJob program = to_job_msg(toolpaths, setup.frame, header);
      program.rapids_checked_by_stock = true;  // run_job refuses a job with a rapid into the stock
      // The program sets the setup's own work offset, as the job's programs do.
      if (setup.work_offset) set_work_offset(program, *setup.work_offset);
      program.setup_note = "for setup " + std::to_string(index + 1) + " (" + setup.name + "), " + setup.face_down +
                           " down: " + setup.fixture.description;
      if (report.workpiece_on_table) {
        // 3+2: one program through every setup, the part indexed on the trunnion's table between them.
        program.workpiece_on_table = to_point_msg(report.workpiece_on_table->pose.translation());
        program.setup_note = "at machine zero: identity kinematics, the program's X Y Z are the machine's axes; " +
                             std::to_string(report.setups.size()) + " setups indexed in one clamping: " +
                             setup.fixture.description;
      }
      result.programs.push_back(program);
    }
    if (!goal.output_dir.empty() && !report.setups.empty()) {
      sheet::SheetJob sheet;
      sheet.title = goal.job_file.empty() ? "the goal's job" : goal.job_file;
      sheet.report = &report;
      const Mesh part = received ? *received : job::read_part(spec);
      sheet.part = &part;
      sheet.toolpaths = planned;
      sheet::write_setup_sheet(goal.output_dir + "/setup_sheet.html", sheet);
    }
    cancelled = report.cancelled;
    // Faces the job was to finish, left above their limit, fail it as they fail `rosmill job` (exit status 4).
    result.success = !report.cancelled && !report.unfinished();
    result.message = report.cancelled ? "cancelled after " + std::to_string(report.operations.size()) + " of " +
                                            std::to_string(operations) + " operations"
                     : report.unfinished()
                         ? "ran " + std::to_string(operations) + " operations, but " +
                               std::to_string(report.surface.unfinished_faces) +
                               " faces it was to finish are left above their limit (" +
                               decimal_text(report.surface.unfinished_area, 1) + " mm^2, up to " +
                               decimal_text(report.surface.max_left_mm, 3) +
                               " mm; the job's accept_unfinished: true accepts it)"
                         : "ran " + std::to_string(operations) + " operations";
  } catch (const std::exception& e) {
    result.success = false;
    result.message = e.what();
  }
  return result;
}

JobActionServer::JobActionServer(::ros::NodeHandle& nh, const ::ros::NodeHandle& pnh, const std::string& frame_id,
                                 const ToolTable& tools, const PresetTable& presets,
                                 std::function<std::shared_ptr<const Mesh>()> received_mesh,
                                 const tf2_ros::Buffer* tf)
    : frame_id_(frame_id), server_(nh, "plan_job", [this](const PlanJobGoalConstPtr& g) { on_goal(g); }, false) {
  job::JobRequest& request = context_.request;
  request.tools = &tools;
  request.presets = &presets;
  request.dialect = string_param(pnh, "dialect", "linuxcnc");
  const std::string machine = string_param(pnh, "machine", "");
  if (!machine.empty()) request.machine = gcode::load_machine_limits(machine);
  request.no_limits = bool_param(pnh, "no_limits", false);
  request.verify_rs274 = bool_param(pnh, "verify_rs274", false);
  job::job_options(request);  // the parameters' errors (an unknown dialect) now, not at the first goal
  context_.received_mesh = std::move(received_mesh);
  const WorkOffsetSource offset = work_offset_source(pnh);
  if (!offset.workpiece_frame.empty()) context_.work_offset = [offset, tf] { return offset.now(tf); };
  context_.setup_frame = [this](const SetupFrame& setup, size_t index) {
    // A setup that neither turns nor moves the part (+Z at the workpiece datum) is the workpiece frame itself.
    if (setup.identity()) return frame_id_;
    const std::string id = job_setup_frame_id(frame_id_, index);
    setup_frames_.publish_as(frame_id_, id, setup);
    return id;
  };
  context_.cancel_requested = [this] { return server_.isPreemptRequested(); };
  context_.feedback = [this](const PlanJobFeedback& fb) { server_.publishFeedback(fb); };
  job_markers_ = nh.advertise<visualization_msgs::MarkerArray>("job_markers", 1, true);
  stock_markers_ = nh.advertise<visualization_msgs::MarkerArray>("stock_markers", 1, true);
  server_.start();
}

void JobActionServer::on_goal(const PlanJobGoalConstPtr& goal) {
  std_msgs::Header header;
  header.frame_id = frame_id_;
  header.stamp = ::ros::Time::now();
  JobMarkers view(header);
  JobGoalContext context = context_;
  context.show = [&](const job::OperationView& v) {
    job_markers_.publish(view.add_operation(v));
    stock_markers_.publish(view.stock(v));
  };
  context.show_surface = [&](const Mesh& part, const job::SurfaceAccount& surface) {
    job_markers_.publish(view.add_surface(part, surface));
  };
  bool cancelled = false;
  const PlanJobResult result = run_job_goal(*goal, context, cancelled);
  if (!result.success) ROS_WARN("plan_job: %s", result.message.c_str());
  finish_goal(server_, result, cancelled, result.success);
}

}  // namespace rosmill::edge
