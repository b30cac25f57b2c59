// Reading the job file's YAML: a mapping with its place in the file ("setups[1].fixture") whose errors name the
// file, the line and the field, and the paths the job names. Private to the job area.
#pragma once
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "rosmill/error.hpp"
#include "rosmill/geometry/types.hpp"

namespace rosmill::core::job {

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
  // The place of a field within the file ("operations[2].tool"), for a mapping nested in it.
  std::string place(const std::string& key) const { return place_.empty() ? key : place_ + "." + key; }
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

  // [x, y, z], every number finite.
  Vec3 vector3(const std::string& key) const {
    const YAML::Node v = node_[key];
    if (!v.IsSequence() || v.size() != 3) throw Error(where_at(v, key), "expected [x, y, z]");
    Vec3 out;
    for (int a = 0; a < 3; ++a) {
      out[a] = converted<double>(v[a], key, "expected a number");
      if (!std::isfinite(out[a])) throw Error(where_at(v, key), "expected finite numbers");
    }
    return out;
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

inline std::string resolve(const std::string& path, const std::string& folder) {
  if (path.rfind("primitive:", 0) == 0 || path.empty()) return path;
  const std::filesystem::path p(path);
  return p.is_absolute() ? path : (std::filesystem::path(folder) / p).lexically_normal().string();
}

// Whether a named file exists; a name the system cannot look up (too long, a loop of links) is refused at `where`.
inline bool file_exists(const std::string& path, const std::string& where) {
  std::error_code failure;
  const bool exists = std::filesystem::exists(path, failure);
  if (failure) throw Error(where, "cannot look up " + path + ": " + failure.message());
  return exists;
}


}  // namespace rosmill::core::job
