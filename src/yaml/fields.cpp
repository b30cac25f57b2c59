#include "rosmill/yaml/fields.hpp"

#include <cmath>
#include <sstream>

namespace rosmill::core::yaml {

YAML::Node parse(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(file + ":" + std::to_string(e.mark.line + 1), "not valid YAML: " + e.msg);
  }
}

std::string line_of(const YAML::Node& node, const std::string& file) {
  const int line = node ? node.Mark().line : -1;
  return line >= 0 ? file + ":" + std::to_string(line + 1) : file;
}

Fields::Fields(const YAML::Node& node, std::string file, std::string place, const std::set<std::string>& known)
    : node_(node), file_(std::move(file)), place_(std::move(place)) {
  if (!node.IsMap()) throw Error(where_at(node, ""), "expected a mapping of fields");
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) throw Error(where_at(kv.first, ""), "a field's name must be a text");
    const std::string key = kv.first.Scalar();
    if (known.count(key)) continue;
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    throw Error(where_at(kv.first, key), "unknown field (expected one of " + list + ")");
  }
}

std::string Fields::where_at(const YAML::Node& at, const std::string& key) const {
  const std::string field = key.empty() ? place_ : place(key);
  return line_of(at, file_) + (field.empty() ? "" : " " + field);
}

void Fields::fail(const std::string& key, const std::string& what) const { throw Error(where(key), what); }

std::string Fields::text(const std::string& key, const std::string& fallback, bool required) const {
  const YAML::Node v = node_[key];
  if (!v) {
    if (required) fail(key, "missing (required)");
    return fallback;
  }
  if (!v.IsScalar() || v.Scalar().empty()) throw Error(where_at(v, key), "expected a text");
  return v.Scalar();
}

double Fields::number(const std::string& key, double fallback, double lo, double hi) const {
  const YAML::Node v = node_[key];
  if (!v) return fallback;
  const double x = converted<double>(v, key, "expected a number");
  if (!std::isfinite(x)) throw Error(where_at(v, key), "expected a finite number, got " + v.Scalar());
  if (x < lo || x > hi) {
    std::ostringstream m;
    m << "must lie in [" << lo << ", " << hi << "], got " << v.Scalar();
    throw Error(where_at(v, key), m.str());
  }
  return x;
}

double Fields::required_number(const std::string& key, double lo, double hi) const {
  if (!has(key)) fail(key, "missing (required)");
  return number(key, NAN, lo, hi);
}

double Fields::positive(const std::string& key, double fallback, double hi) const {
  const YAML::Node v = node_[key];
  if (!v) return fallback;
  const double x = converted<double>(v, key, "expected a number");
  if (!(x > 0) || !std::isfinite(x) || x > hi) {
    std::ostringstream m;
    m << "must be greater than 0";
    if (hi < kUnbounded) m << " and at most " << hi;
    m << ", got " << v.Scalar();
    throw Error(where_at(v, key), m.str());
  }
  return x;
}

double Fields::required_positive(const std::string& key, double hi) const {
  if (!has(key)) fail(key, "missing (required)");
  return positive(key, NAN, hi);
}

Vec3 Fields::vector3(const std::string& key) const {
  const YAML::Node v = node_[key];
  if (!v.IsSequence() || v.size() != 3) throw Error(where_at(v ? v : node_, key), "expected [x, y, z]");
  Vec3 out;
  for (int a = 0; a < 3; ++a) {
    out[a] = converted<double>(v[a], key, "expected a number");
    if (!std::isfinite(out[a])) throw Error(where_at(v, key), "expected finite numbers");
  }
  return out;
}

bool Fields::flag(const std::string& key, bool fallback) const {
  const YAML::Node v = node_[key];
  if (!v) return fallback;
  return converted<bool>(v, key, "expected true or false");
}

}  // namespace rosmill::core::yaml
