// Reading the package's YAML files (the tool table, the machine file, the presets, a pose, a job): every error names
// the file, the line and the field ("tools.yaml:22 tools[5].feed: expected a number, got 'fast'"), so that a person
// finds what to change without reading the reader.
#pragma once
#include <yaml-cpp/yaml.h>

#include <set>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core::yaml {

// `text` parsed as YAML; a syntax error names the file and its line.
YAML::Node parse(const std::string& text, const std::string& file);

// "file:line" of a node (its first line; the file's own name where the node has no place, an empty document).
std::string line_of(const YAML::Node& node, const std::string& file);

// A mapping of a file with its place in it ("setups[1].fixture", "" at the top) and the fields it may hold: a field
// it does not know is refused, naming those it does.
class Fields {
 public:
  Fields(const YAML::Node& node, std::string file, std::string place, const std::set<std::string>& known);

  bool has(const std::string& key) const { return static_cast<bool>(node_[key]); }
  // The place of a field within the file ("operations[2].tool"), for a mapping nested in it.
  std::string place(const std::string& key) const { return place_.empty() ? key : place_ + "." + key; }
  YAML::Node node(const std::string& key) const { return node_[key]; }
  const std::string& file() const { return file_; }
  // "file:line place.key": the field's line, or the mapping's where the field is absent.
  std::string where(const std::string& key) const { return where_at(node_[key] ? node_[key] : node_, key); }
  std::string where_at(const YAML::Node& at, const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  // A text (required: absent is an error; otherwise `fallback`).
  std::string text(const std::string& key, const std::string& fallback, bool required = false) const;
  // A finite number in [lo, hi]; `fallback` when absent (NaN: none), an error when required.
  static constexpr double kUnbounded = 1e300;
  double number(const std::string& key, double fallback, double lo = -kUnbounded, double hi = kUnbounded) const;
  double required_number(const std::string& key, double lo = -kUnbounded, double hi = kUnbounded) const;
  // A number greater than 0 (and at most `hi`); `fallback` when absent, an error when required.
  double positive(const std::string& key, double fallback, double hi = kUnbounded) const;
  double required_positive(const std::string& key, double hi = kUnbounded) const;
  // [x, y, z], every number finite.
  Vec3 vector3(const std::string& key) const;
  bool flag(const std::string& key, bool fallback) const;

  template <class T>
  T converted(const YAML::Node& v, const std::string& key, const std::string& expected) const {
    try {
      return v.as<T>();
    } catch (const YAML::Exception&) {
      throw Error(where_at(v, key), expected + (v.IsScalar() ? ", got '" + v.Scalar() + "'" : ""));
    }
  }

 private:
  YAML::Node node_;
  std::string file_, place_;
};

}  // namespace rosmill::core::yaml
