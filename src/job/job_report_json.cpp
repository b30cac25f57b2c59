// The job's report as `rosmill job --json` prints it (millimetres, mm^3, seconds).
#include "rosmill/job/run_job.hpp"
#include "rosmill/verify/engagement_json.hpp"

namespace rosmill::core::job {
namespace {

nlohmann::json vec(const Vec3& v) { return {v.x() + 0.0, v.y() + 0.0, v.z() + 0.0}; }

nlohmann::json box(const Box3& b) { return {{"min", vec(b.min)}, {"max", vec(b.max)}}; }

// A placement's 4x4 matrix, row-major: a point of its child frame in its parent's.
nlohmann::json matrix(const Placement& p) {
  nlohmann::json m = nlohmann::json::array();
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) m.push_back(p.pose.matrix()(i, k) + 0.0);
  return m;
}

nlohmann::json operation_json(const OperationReport& r) {
  const Cutter& c = r.tool_used.cutter;
  nlohmann::json o = {{"name", r.name},
                      {"strategy", r.strategy},
                      {"tool", r.tool},
                      {"tool_number", r.tool_used.id},
                      {"cutter", {{"type", cutter_type_name(c.type)}, {"diameter", c.diameter},
                                  {"corner_radius", c.corner_radius}}},
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
                      {"engagement_seconds", r.engagement_seconds},
                      {"remove_seconds", r.remove_seconds},
                      {"verify_seconds", r.verify_seconds},
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
  std::vector<UnclearedPatch> left;
  for (const PlanReport& p : r.plan_reports) {
    left.insert(left.end(), p.uncleared.begin(), p.uncleared.end());
    if (p.slot_length_mm > 0)
      o["slot"] = {{"length_mm", p.slot_length_mm}, {"max_engagement_deg", p.slot_max_engagement_deg},
                   {"feed", p.slot_feed}};
  }
  o["uncleared"] = uncleared_json<nlohmann::json>(left);
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
                      {"frame", matrix(s.frame.placement)},
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

nlohmann::json face_json(const FaceLeft& f) {
  nlohmann::json j = {{"face", f.face},
                      {"area", f.area},
                      {"centroid", vec(f.centroid)},
                      {"normal", vec(f.normal)},
                      {"setup", f.setup},
                      {"verdict", verdict_name(f.verdict)},
                      {"min_left_mm", f.min_left_mm},
                      {"max_left_mm", f.max_left_mm},
                      {"most_at", vec(f.most_at)},
                      {"least_at", vec(f.least_at)},
                      {"facets", f.facets}};
  if (f.verdict != FaceVerdict::NotAsked) j["allowance"] = f.allowance, j["limit"] = f.limit;
  if (f.verdict == FaceVerdict::Above) {
    nlohmann::json reasons = nlohmann::json::object();
    for (int r = 0; r < kLeftReasons; ++r)
      if (f.reason_area[r] > 0) reasons[reason_name(static_cast<LeftReason>(r))] = f.reason_area[r];
    j["above"] = {{"area", f.above_area}, {"centroid", vec(f.above_centroid)},
                  {"reason", reason_name(f.main_reason())}, {"reasons", reasons}};
  }
  return j;
}

nlohmann::json surface_json(const SurfaceAccount& a) {
  nlohmann::json faces = nlohmann::json::array();
  for (const FaceLeft& f : a.faces) faces.push_back(face_json(f));
  return {{"samples", a.samples},         {"asked_faces", a.asked_faces},   {"min_left_mm", a.min_left_mm},
          {"max_left_mm", a.max_left_mm}, {"unfinished_faces", a.unfinished_faces},
          {"unfinished_area", a.unfinished_area}, {"seconds", a.seconds}, {"faces", faces}};
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
  if (report.surface.done) {
    j["surface"] = surface_json(report.surface);
    j["accept_unfinished"] = report.accept_unfinished;
    j["unfinished"] = report.unfinished();
  }
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
