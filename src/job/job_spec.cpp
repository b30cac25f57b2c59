#include "rosmill/job/job_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "rosmill/error.hpp"
#include "rosmill/input_file.hpp"

namespace rosmill::core::job {
namespace {

// A mapping of the job file with its place ("operations[2]") for errors that name the file, line and field.
class Fields {
 public:
  Fields(const YAML::Node& node, std::string file, std::string place, const std::set<std::string>& known)
      : node_(node), file_(std::move(file)), place_(std::move(place)) {
    if (!node.IsMap()) throw Error(where_at(node, ""), "expected a mapping of fields");
    for (const auto& kv : node) {
      const std::string key = kv.first.Scalar();
      if (!known.count(key)) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
        throw Error(where_at(kv.first, key), "unknown field (expected one of " + list + ")");
      }
    }
  }

  bool has(const std::string& key) const { return static_cast<bool>(node_[key]); }
  YAML::Node node(const std::string& key) const { return node_[key]; }
  std::string where(const std::string& key) const { return where_at(node_[key] ? node_[key] : node_, key); }

  std::string text(const std::string& key, const std::string& fallback, bool required = false) const {
    const YAML::Node v = node_[key];
    if (!v) {
      if (required) throw Error(where_at(node_, key), "missing (required)");
      return fallback;
    }
    if (!v.IsScalar() || v.Scalar().empty()) throw Error(where_at(v, key), "expected a text");
    return v.Scalar();
  }

  // A number in [lo, hi] (NaN when absent and `fallback` is NaN).
  double number(const std::string& key, double fallback, double lo, double hi) const {
    const YAML::Node v = node_[key];
    if (!v) return fallback;
    const double x = converted<double>(v, key, "expected a number");
    if (!std::isfinite(x) || x < lo || x > hi) {
      std::ostringstream m;
      m << "must lie in [" << lo << ", " << hi << "], got " << v.Scalar();
      throw Error(where_at(v, key), m.str());
    }
    return x;
  }

  bool flag(const std::string& key, bool fallback) const {
    const YAML::Node v = node_[key];
    if (!v) return fallback;
    return converted<bool>(v, key, "expected true or false");
  }

  template <class T>
  T converted(const YAML::Node& v, const std::string& key, const std::string& expected) const {
    try {
      return v.as<T>();
    } catch (const YAML::Exception&) {
      throw Error(where_at(v, key), expected + (v.IsScalar() ? ", got '" + v.Scalar() + "'" : ""));
    }
  }

  std::string where_at(const YAML::Node& at, const std::string& key) const {
    const std::string field = key.empty() ? place_ : place_.empty() ? key : place_ + "." + key;
    return file_ + ":" + std::to_string(at.Mark().line + 1) + (field.empty() ? "" : " " + field);
  }

 private:
  const YAML::Node& node_;
  std::string file_, place_;
};

std::string resolve(const std::string& path, const std::string& folder) {
  if (path.rfind("primitive:", 0) == 0 || path.empty()) return path;
  const std::filesystem::path p(path);
  return p.is_absolute() ? path : (std::filesystem::path(folder) / p).lexically_normal().string();
}

// Whether a named file exists; a name the system cannot look up (too long, a loop of links) is refused at `where`.
bool file_exists(const std::string& path, const std::string& where) {
  std::error_code failure;
  const bool exists = std::filesystem::exists(path, failure);
  if (failure) throw Error(where, "cannot look up " + path + ": " + failure.message());
  return exists;
}

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

// `box_stock`: the stock is the part's box, where a first operation finds no rest material to keep to (a stock
// scanned after machining, or a casting, may well start with one).
OperationSpec read_operation(const YAML::Node& node, const std::string& file, size_t index, bool box_stock) {
  const Fields f(node, file, "operations[" + std::to_string(index) + "]",
                 {"name", "strategy", "tool", "stepover", "stepdown", "allowance", "tolerance", "setup", "rest",
                  "rest_threshold"});
  OperationSpec op;
  op.line = node.Mark().line + 1;
  op.strategy = f.text("strategy", "", true);
  op.name = f.text("name", op.strategy);
  op.tool = f.text("tool", "", true);
  op.stepover = f.number("stepover", NAN, 1e-3, 1000);
  op.stepdown = f.number("stepdown", NAN, 1e-3, 1000);
  op.allowance = f.number("allowance", 0.0, 0, 100);
  op.tolerance = f.number("tolerance", NAN, 1e-6, 10);
  op.setup = f.text("setup", "+Z");
  op.rest = f.flag("rest", false);
  op.rest_threshold = f.number("rest_threshold", 0.1, 0, 100);
  if (f.has("rest_threshold") && !op.rest)
    throw Error(f.where("rest_threshold"), "only a rest operation (rest: true) has one");
  if (op.rest && index == 0 && box_stock)
    throw Error(f.where("rest"), "the first operation on a box stock has no earlier one to leave rest material (a "
                                 "stock scanned after machining, stock: {cloud: FILE}, may start with a rest operation)");
  return op;
}

}  // namespace

JobSpec parse_job(const std::string& text, const std::string& name, const std::string& folder) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(name + ":" + std::to_string(e.mark.line + 1), "not valid YAML: " + e.msg);
  }
  const Fields f(root, name, "", {"part", "units", "resolution", "rapid_feed", "stock", "operations"});
  JobSpec job;
  job.source = name;
  job.part = resolve(f.text("part", "", true), folder);
  if (job.part.rfind("primitive:", 0) != 0 && !file_exists(job.part, f.where("part")))
    throw Error(f.where("part"), "no file " + job.part);
  if (f.has("units")) job.units = parse_units(f.text("units", "mm"), f.where("units"));
  job.resolution = f.number("resolution", 0.5, 0.01, 100);
  job.rapid_feed = f.number("rapid_feed", 5000.0, 1, 1e6);
  if (f.has("stock")) job.stock = read_stock(f.node("stock"), name, folder);
  const YAML::Node ops = f.node("operations");
  if (!ops) throw Error(f.where("operations"), "missing (required): the operations in machining order");
  if (!ops.IsSequence() || ops.size() == 0) throw Error(f.where("operations"), "expected a list of operations");
  for (size_t k = 0; k < ops.size(); ++k) job.operations.push_back(read_operation(ops[k], name, k, job.stock.kind == StockSpec::Kind::Box));
  return job;
}

JobSpec read_job(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
  return parse_job(read_input_file(path), path, folder.string());
}

}  // namespace rosmill::core::job
