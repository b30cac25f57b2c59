// The job's report as `rosmill job --json` prints it (millimetres, mm^3, seconds).
#include "rosmill/job/run_job.hpp"
#include "rosmill/verify/engagement_json.hpp"

namespace rosmill::core::job {
namespace {

nlohmann::json vec(const Vec3& v) { return {v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}; }

nlohmann::json box(const Box3& b) { return {{"min", vec(b.min)}, {"max", vec(b.max)}}; }

nlohmann::json operation_json(const OperationReport& r) {
  nlohmann::json o = {{"name", r.name},
                      {"strategy", r.strategy},
                      {"tool", r.tool},
                      {"setup", r.setup},
                      {"setup_index", r.setup_index},
                      {"moves", r.moves},
                      {"cutting_mm", r.cutting_mm},
                      {"rapid_mm", r.rapid_mm},
                      {"air_feed_mm", r.air_feed_mm},
                      {"air_cut_share", r.air_cut_share},
                      {"removed_mm3", r.removed_mm3},
                      {"time_s", r.time_s},
                      {"plan_seconds", r.plan_seconds},
                      {"rapid_collision_line", r.collision_line},
                      {"min_left_mm", r.min_left_mm},
                      {"max_left_mm", r.max_left_mm},
                      {"gouge_mm", r.gouge_mm},
                      {"gouge_move", r.gouge_move},
                      {"rest", r.rest},
                      {"rest_cells", r.rest_cells},
                      {"nothing_to_cut", r.nothing_to_cut}};
  if (!r.program.empty()) o["program"] = r.program;
  o["roughing"] = r.roughing;
  if (r.engagement_measured) {
    o["engagement"] = verify::engagement_json<nlohmann::json>(r.engagement);
    o["feeds_from_engagement"] = r.feeds_from_engagement;
  }
  return o;
}

nlohmann::json setup_json(const SetupReport& s) {
  nlohmann::json fixture_boxes = nlohmann::json::array();
  for (const fixture::FixtureBox& b : s.fixture.boxes) fixture_boxes.push_back({{"name", b.name}, {"box", box(b.box)}});
  nlohmann::json j = {{"name", s.name},
                      {"direction", vec(s.direction)},
                      {"source", s.source},
                      {"face_down", s.face_down},
                      {"datum", datum_name(s.datum)},
                      {"datum_point", vec(s.datum_point)},
                      {"stock", box(s.stock)},
                      {"fixture", {{"description", s.fixture.description}, {"seat", s.fixture.seat},
                                   {"boxes", fixture_boxes}}},
                      {"operations", s.operations},
                      {"finished_area", s.finished_area},
                      {"time_s", s.time_s}};
  if (s.work_offset)
    j["work_offset"] = {{"code", s.work_offset->code()}, {"origin", vec(s.work_offset->origin)},
                        {"rotation_deg", s.work_offset->rotation_deg}};
  else
    j["work_offset"] = {{"code", "G54"}, {"origin", nullptr}};
  if (s.index) j["index"] = {{"a_deg", s.index->a}, {"c_deg", s.index->c}, {"indexing_s", s.indexing_s}};
  if (!s.program.empty()) j["program"] = s.program;
  return j;
}

}  // namespace

nlohmann::json to_json(const JobReport& report) {
  nlohmann::json ops = nlohmann::json::array(), setups = nlohmann::json::array();
  for (const OperationReport& r : report.operations) ops.push_back(operation_json(r));
  for (const SetupReport& s : report.setups) setups.push_back(setup_json(s));
  nlohmann::json j = {{"operations", ops},
                      {"setups", setups},
                      {"stock_mm3", report.stock_mm3},
                      {"stock_box", box(report.stock_box)},
                      {"left_mm3", report.left_mm3},
                      {"removed_mm3", report.removed_mm3},
                      {"air_cut_share", report.air_cut_share},
                      {"time_s", report.time_s},
                      {"min_left_mm", report.min_left_mm},
                      {"max_left_mm", report.max_left_mm},
                      {"gouge_mm", report.gouge_mm},
                      {"stock_bytes", report.stock_bytes},
                      {"cancelled", report.cancelled}};
  j["indexed"] = report.indexed;
  if (report.workpiece_on_table)
    j["workpiece_on_table"] = {{"translation", vec(report.workpiece_on_table->pose.translation())}};
  if (report.program_check.done) {
    const JobReport::ProgramCheck& c = report.program_check;
    j["program_check"] = {{"runs", c.runs},          {"gouge_mm", c.gouge_mm},       {"gouge_line", c.gouge_line},
                          {"min_left_mm", c.min_left_mm}, {"max_left_mm", c.max_left_mm}, {"left_mm3", c.left_mm3},
                          {"seconds", c.seconds}};
  }
  if (report.part_area > 0) {
    nlohmann::json places = nlohmann::json::array();
    for (const setups::Unreached& u : report.unreachable)
      places.push_back({{"patch", u.patch}, {"reason", u.reason}, {"area", u.area}, {"centroid", vec(u.centroid)},
                        {"normal", vec(u.normal)}});
    j["setups_chosen"] = report.setups_chosen;
    j["part_area"] = report.part_area;
    j["unreachable_area"] = report.unreachable_area;
    j["unreachable"] = places;
  }
  return j;
}

}  // namespace rosmill::core::job
