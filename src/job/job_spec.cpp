#include "rosmill/job/job_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "job_files.hpp"
#include "rosmill/cutter/tool_table.hpp"
#include "rosmill/error.hpp"
#include "rosmill/gcode/work_offset.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/input_file.hpp"
#include "setup_yaml.hpp"

namespace rosmill::core::job {
namespace {

StockSpec read_stock(const YAML::Node& node, const std::string& file, const std::string& folder) {
  const Fields f(node, file, "stock", {"box", "mesh", "cloud", "table_z", "units"});
  StockSpec s;
  const int kinds = f.has("box") + f.has("mesh") + f.has("cloud");
  if (kinds != 1) throw Error(f.where(""), "give exactly one of box, mesh or cloud");
  if (f.has("box")) {
    const YAML::Node box = f.node("box");
    const Fields b(box, file, "stock.box", {"margin"});
    s.margin = b.number("margin", 5.0, 0, 1000);
    if (f.has("table_z") || f.has("units")) throw Error(f.where("table_z"), "only a cloud stock has table_z and units");
    return s;
  }
  s.kind = f.has("mesh") ? StockSpec::Kind::Mesh : StockSpec::Kind::Cloud;
  s.file = resolve(f.text(f.has("mesh") ? "mesh" : "cloud", ""), folder);
  const bool primitive = s.file.rfind("primitive:", 0) == 0;
  if (primitive && s.kind == StockSpec::Kind::Cloud) throw Error(f.where("cloud"), "a cloud stock must be a file");
  const std::string field = f.has("mesh") ? "mesh" : "cloud";
  if (!primitive && !file_exists(s.file, f.where(field))) throw Error(f.where(field), "no file " + s.file);
  if (s.kind == StockSpec::Kind::Mesh && (f.has("table_z") || f.has("units")))
    throw Error(f.where("table_z"), "only a cloud stock has table_z and units (a mesh takes the job's units)");
  s.table_z = f.number("table_z", 0.0, -1e5, 1e5);
  if (f.has("units")) s.units = parse_units(f.text("units", "mm"), f.where("units"));
  else if (s.kind == StockSpec::Kind::Cloud) s.units = Units::Metre;  // clouds, as ROS writes them
  return s;
}

// {number: 7, type: flat, diameter: 4} as the spec resolve_tool reads ("flat:4@7").
std::string read_tool_mapping(const Fields& t) {
  const double number = t.number("number", NAN, 1, kMaxToolNumber);
  if (std::isnan(number))
    throw Error(t.where("number"), "missing (required): the tool's number in the controller's tool table");
  if (number != std::floor(number)) throw Error(t.where("number"), "must be a whole number");
  const std::string type = t.text("type", "", true);
  const double d = t.number("diameter", NAN, 1e-3, 500);
  if (std::isnan(d)) throw Error(t.where("diameter"), "missing (required)");
  const double r = t.number("corner_radius", NAN, 1e-3, 250);
  if (type != "bull" && t.has("corner_radius"))
    throw Error(t.where("corner_radius"), "only a bull nose (type: bull) has one");
  Cutter c;
  if (type == "flat") c = Cutter::flat(d);
  else if (type == "ball") c = Cutter::ball(d);
  else if (type != "bull") throw Error(t.where("type"), "must be flat, ball or bull, got '" + type + "'");
  else if (std::isnan(r)) throw Error(t.where("corner_radius"), "missing (required for a bull nose)");
  else if (r > 0.5 * d) throw Error(t.where("corner_radius"), "is larger than half the diameter");
  else c = Cutter::bull(d, r);
  return inline_tool_spec(c, static_cast<int>(number));
}

// An operation's tool: an id of the tool table, an inline cutter with its number ("flat:4@7"), or the same as a
// mapping ({number: 7, type: flat, diameter: 4}, corner_radius for a bull nose). Every tool of a job is loaded by
// its number, so an inline tool without one is refused here, before anything is planned.
std::string read_operation_tool(const Fields& f, const std::string& file) {
  if (!f.has("tool")) throw Error(f.where("tool"), "missing (required)");
  const YAML::Node node = f.node("tool");
  if (node.IsMap()) return read_tool_mapping(Fields(node, file, f.place("tool"), {"number", "type", "diameter",
                                                                                   "corner_radius"}));
  const std::string spec = f.text("tool", "", true);
  const bool table_id = spec.find_first_not_of("0123456789") == std::string::npos;
  if (!table_id && resolve_tool(spec, nullptr, f.where("tool")).id == kNoToolNumber)
    throw Error(f.where("tool"), "'" + spec + "' has no number in the controller's tool table: write " + spec +
                                     "@N (N: its tool number), a mapping {number: N, type: ..., diameter: ...}, or a "
                                     "tool id of the tool table");
  return spec;
}

// One operation at `place` ("operations[2]", "setups[1].operations[0]"). `first_on_box`: the first operation of
// the job on a box stock, where no earlier one left rest material to keep to (a stock scanned after machining, or
// a casting, may well start with one). `setup_field`: the older form, where an operation names its setup.
OperationSpec read_operation(const YAML::Node& node, const std::string& file, const std::string& place,
                             bool first_on_box, bool setup_field) {
  const Fields f(node, file, place,
                 {"name", "strategy", "tool", "stepover", "stepdown", "allowance", "tolerance", "angle", "engagement",
                  "setup", "rest", "rest_threshold"});
  OperationSpec op;
  op.line = node.Mark().line + 1;
  op.strategy = f.text("strategy", "", true);
  op.name = f.text("name", op.strategy);
  op.tool = read_operation_tool(f, file);
  op.stepover = f.number("stepover", NAN, 1e-3, 1000);
  op.stepdown = f.number("stepdown", NAN, 1e-3, 1000);
  op.allowance = f.number("allowance", 0.0, 0, 100);
  op.tolerance = f.number("tolerance", NAN, 1e-6, 10);
  op.angle = f.number("angle", NAN, -360, 360);
  op.engagement = f.number("engagement", NAN, 1e-3, 180);
  if (f.has("setup") && !setup_field)
    throw Error(f.where("setup"), "an operation of a job with setups runs in its setup (give it there)");
  op.setup = f.text("setup", "+Z");
  op.rest = f.flag("rest", false);
  op.rest_threshold = f.number("rest_threshold", 0.1, 0, 100);
  if (f.has("rest_threshold") && !op.rest)
    throw Error(f.where("rest_threshold"), "only a rest operation (rest: true) has one");
  if (op.rest && first_on_box)
    throw Error(f.where("rest"), "the first operation on a box stock has no earlier one to leave rest material (a "
                                 "stock scanned after machining, stock: {cloud: FILE}, may start with a rest operation)");
  return op;
}

std::vector<OperationSpec> read_operations(const Fields& f, const std::string& file, const std::string& place,
                                           bool box_stock_first, bool setup_field) {
  const YAML::Node ops = f.node("operations");
  if (!ops) throw Error(f.where("operations"), "missing (required): the operations in machining order");
  if (!ops.IsSequence() || ops.size() == 0) throw Error(f.where("operations"), "expected a list of operations");
  std::vector<OperationSpec> out;
  for (size_t k = 0; k < ops.size(); ++k)
    out.push_back(read_operation(ops[k], file, (place.empty() ? "" : place + ".") + "operations[" +
                                                   std::to_string(k) + "]",
                                 box_stock_first && k == 0, setup_field));
  return out;
}

// The job's defaults for every setup: its fixture, datum and overlap.
SetupSpec read_defaults(const Fields& f, const std::string& file, Datum datum) {
  SetupSpec d;
  if (f.has("fixture")) d.fixture = read_fixture(f.node("fixture"), file, "fixture");
  d.datum = read_datum(f, "datum", datum);
  d.overlap = f.number("overlap", 1.0, 0, 100);
  return d;
}

SetupSpec read_setup(const YAML::Node& node, const std::string& file, size_t index, const SetupSpec& defaults,
                     const JobSpec& job, std::vector<OperationSpec>& ops) {
  const std::string place = "setups[" + std::to_string(index) + "]";
  const Fields f(node, file, place, {"name", "direction", "fixture", "datum", "overlap", "operations"});
  SetupSpec s = defaults;
  s.line = node.Mark().line + 1;
  if (!f.has("direction")) throw Error(f.where(""), "direction: missing (required): +Z, -X, ... or [x, y, z]");
  s.direction = read_direction(f, "direction", s.name);
  s.name = f.text("name", s.name);
  if (f.has("fixture")) s.fixture = read_fixture(f.node("fixture"), file, place + ".fixture");
  s.datum = read_datum(f, "datum", defaults.datum);
  s.overlap = f.number("overlap", defaults.overlap, 0, 100);
  for (OperationSpec& op :
       read_operations(f, file, place, index == 0 && job.stock.kind == StockSpec::Kind::Box, false)) {
    op.setup = s.name;
    op.setup_index = index;
    ops.push_back(op);
  }
  return s;
}

// The older form: consecutive operations of one setup are that setup (the part's own origin when it is the only one).
void setups_of_operations(JobSpec& job, const Fields& f) {
  for (size_t k = 0; k < job.operations.size(); ++k) {
    OperationSpec& op = job.operations[k];
    if (k == 0 || op.setup != job.operations[k - 1].setup) {
      SetupSpec s = job.setup_defaults;
      const SetupFrame named =
          named_setup(op.setup, job.source + ":" + std::to_string(op.line) + " operations[" + std::to_string(k) + "].setup");
      s.direction = named.tool_axis;
      s.name = named.name;
      s.line = op.line;
      job.setups.push_back(s);
    }
    op.setup = job.setups.back().name;
    op.setup_index = job.setups.size() - 1;
  }
  if (!f.has("datum") && job.setups.size() == 1) job.setups[0].datum = Datum::Workpiece;
}

}  // namespace

const char* datum_name(Datum d) {
  switch (d) {
    case Datum::Workpiece: return "workpiece";
    case Datum::TopCentre: return "top-centre";
    case Datum::Corner: return "corner";
  }
  return "?";
}

SetupSpec default_setup(const JobSpec& job, const Vec3& direction) {
  SetupSpec s = job.setup_defaults;
  s.direction = direction.normalized();
  s.name = setup_name_of(s.direction);
  return s;
}

JobSpec parse_job(const std::string& text, const std::string& name, const std::string& folder) {
  const Fields f(yaml::parse(text, name), name, "",
                 {"part", "units", "resolution", "rapid_feed", "stock", "operations", "setups", "fixture", "datum",
                  "overlap", "held_face", "auto", "accept_unfinished"});
  JobSpec job;
  job.source = name;
  job.accept_unfinished = f.flag("accept_unfinished", false);
  job.part = resolve(f.text("part", "", true), folder);
  if (job.part.rfind("primitive:", 0) != 0 && !file_exists(job.part, f.where("part")))
    throw Error(f.where("part"), "no file " + job.part);
  if (f.has("units")) job.units = parse_units(f.text("units", "mm"), f.where("units"));
  job.resolution = f.number("resolution", 0.5, 0.01, 100);
  job.rapid_feed = f.number("rapid_feed", 5000.0, 1, 1e6);
  if (f.has("stock")) job.stock = read_stock(f.node("stock"), name, folder);
  const bool box = job.stock.kind == StockSpec::Kind::Box;
  job.setup_defaults = read_defaults(f, name, Datum::TopCentre);
  const YAML::Node setups = f.node("setups");
  const bool automatic = setups && setups.IsScalar() && setups.Scalar() == "auto";
  if (f.has("auto") && !automatic) throw Error(f.where("auto"), "only a job with setups: auto has one");
  if (f.has("held_face") && !setups)
    throw Error(f.where("held_face"), "only a job with setups (a list, or auto) has one");
  if (f.has("held_face")) {
    std::string unused;
    job.auto_options.held_face = read_direction(f, "held_face", unused);
  }
  if (!setups) {
    job.finish_by_setup = false;
    job.operations = read_operations(f, name, "", box, true);
    setups_of_operations(job, f);
  } else if (automatic) {
    job.auto_setups = true;
    job.operations = read_operations(f, name, "", box, false);
    if (f.has("auto")) {
      const Fields a(f.node("auto"), name, "auto", {"tool", "min_gain"});
      job.auto_options.tool = a.text("tool", "");
      job.auto_options.min_gain = a.number("min_gain", job.auto_options.min_gain, 0, 0.5);
    }
  } else {
    if (!setups.IsSequence() || setups.size() == 0)
      throw Error(f.where("setups"), "expected auto or a list of setups, each with a direction and its operations");
    if (f.has("operations"))
      throw Error(f.where("operations"), "a job with setups gives each setup its operations");
    for (size_t k = 0; k < setups.size(); ++k)
      job.setups.push_back(read_setup(setups[k], name, k, job.setup_defaults, job, job.operations));
  }
  if (job.setups.size() > size_t(gcode::kWorkOffsets))
    throw Error(f.where("setups"), std::to_string(job.setups.size()) + " setups, more than the six work offsets "
                                                                       "(G54..G59) a program can set");
  return job;
}

JobSpec read_job(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
  return parse_job(read_input_file(path), path, folder.string());
}

}  // namespace rosmill::core::job
