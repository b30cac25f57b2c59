#include "setup_yaml.hpp"

#include "rosmill/geometry/setup_frame.hpp"

namespace rosmill::core::job {
namespace {

fixture::ViseSpec read_vise(const YAML::Node& node, const std::string& file, const std::string& place) {
  const Fields f(node, file, place, {"jaw_width", "jaw_height", "jaw_thickness", "opening", "grip", "floor", "clamp"});
  fixture::ViseSpec v;
  v.jaw_width = f.number("jaw_width", v.jaw_width, 1, 2000);
  v.jaw_height = f.number("jaw_height", v.jaw_height, 1, 500);
  v.jaw_thickness = f.number("jaw_thickness", v.jaw_thickness, 1, 500);
  v.opening = f.number("opening", v.opening, 1, 2000);
  v.grip = f.number("grip", v.grip, 0.1, 500);
  v.floor = f.number("floor", v.floor, 0, 1000);
  const std::string clamp = f.text("clamp", "y");
  if (clamp != "x" && clamp != "y") throw Error(f.where("clamp"), "must be x or y (the setup's axis the jaws close along)");
  v.clamp = clamp[0];
  return v;
}

fixture::ClampsSpec read_clamps(const YAML::Node& node, const std::string& file, const std::string& place) {
  const Fields f(node, file, place, {"count", "length", "width", "height", "overlap"});
  fixture::ClampsSpec c;
  const double count = f.number("count", 4, 2, 4);
  if (count != 2 && count != 4) throw Error(f.where("count"), "must be 2 or 4");
  c.count = static_cast<int>(count);
  c.length = f.number("length", c.length, 1, 1000);
  c.width = f.number("width", c.width, 1, 1000);
  c.height = f.number("height", c.height, 1, 1000);
  c.overlap = f.number("overlap", c.overlap, 0.1, 1000);
  return c;
}

fixture::FixtureBox read_box(const YAML::Node& node, const std::string& file, const std::string& place) {
  const Fields f(node, file, place, {"name", "min", "max"});
  fixture::FixtureBox b;
  b.name = f.text("name", place);
  if (!f.has("min") || !f.has("max")) throw Error(f.where(""), "give min: [x, y, z] and max: [x, y, z] (mm)");
  b.box.add(f.vector3("min"));
  b.box.add(f.vector3("max"));
  if (!((f.vector3("max") - f.vector3("min")).array() > 0).all())
    throw Error(f.where("max"), "must lie above min on every axis");
  return b;
}

std::vector<fixture::FixtureBox> read_boxes(const Fields& f, const std::string& key, const std::string& file,
                                            const std::string& place) {
  const YAML::Node list = f.node(key);
  if (!list.IsSequence() || list.size() == 0) throw Error(f.where(key), "expected a list of boxes");
  std::vector<fixture::FixtureBox> boxes;
  for (size_t k = 0; k < list.size(); ++k)
    boxes.push_back(read_box(list[k], file, place + "." + key + "[" + std::to_string(k) + "]"));
  return boxes;
}

}  // namespace

Vec3 read_direction(const Fields& f, const std::string& key, std::string& name) {
  const YAML::Node v = f.node(key);
  if (v.IsScalar()) {
    try {
      const SetupFrame s = named_setup(v.Scalar(), f.where(key));
      name = s.name;
      return s.tool_axis;
    } catch (const Error& e) {
      throw Error(f.where(key), "expected +Z, -Z, +X, -X, +Y, -Y or [x, y, z], got '" + v.Scalar() + "'");
    }
  }
  const Vec3 d = f.vector3(key);
  if (d.norm() < 1e-9) throw Error(f.where(key), "the direction must not be zero");
  name = setup_name_of(d.normalized());
  return d.normalized();
}

Datum read_datum(const Fields& f, const std::string& key, Datum fallback) {
  if (!f.has(key)) return fallback;
  const std::string t = f.text(key, "");
  if (t == "top-centre" || t == "top-center") return Datum::TopCentre;
  if (t == "corner") return Datum::Corner;
  if (t == "workpiece") return Datum::Workpiece;
  throw Error(f.where(key), "expected top-centre, corner or workpiece, got '" + t + "'");
}

fixture::FixtureSpec read_fixture(const YAML::Node& node, const std::string& file, const std::string& place) {
  fixture::FixtureSpec s;
  if (node.IsScalar()) {
    if (node.Scalar() != "table")
      throw Error(file + ":" + std::to_string(node.Mark().line + 1) + " " + place,
                  "expected table, {vise: ...}, {parallels: ..., clamps: ...} or {boxes: [...], seat: MM}");
    return s;
  }
  const Fields f(node, file, place, {"vise", "parallels", "clamps", "boxes", "seat"});
  if (f.has("vise")) {
    if (f.has("parallels") || f.has("clamps") || f.has("boxes") || f.has("seat"))
      throw Error(f.where("vise"), "a vise holds the part alone (it stands on its own parallels)");
    s.kind = fixture::FixtureSpec::Kind::Vise;
    s.vise = read_vise(f.node("vise"), file, place + ".vise");
    return s;
  }
  if (f.has("boxes")) {
    if (f.has("parallels") || f.has("clamps")) throw Error(f.where("boxes"), "give the parallels and clamps as boxes too");
    s.kind = fixture::FixtureSpec::Kind::Boxes;
    s.boxes = read_boxes(f, "boxes", file, place);
    s.seat = f.number("seat", 0, 0, 1000);
    return s;
  }
  if (f.has("seat")) throw Error(f.where("seat"), "only a fixture of boxes has a seat (parallels give theirs)");
  s.kind = fixture::FixtureSpec::Kind::Table;
  if (f.has("parallels")) {
    const Fields p(f.node("parallels"), file, place + ".parallels", {"height", "width"});
    s.parallels = true;
    s.parallel.height = p.number("height", s.parallel.height, 0.5, 500);
    s.parallel.width = p.number("width", s.parallel.width, 0.5, 500);
  }
  if (f.has("clamps")) {
    if (f.node("clamps").IsSequence()) s.boxes = read_boxes(f, "clamps", file, place);
    else s.clamps = read_clamps(f.node("clamps"), file, place + ".clamps");
  }
  return s;
}

}  // namespace rosmill::core::job
