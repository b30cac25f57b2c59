// rosmill slice FILE (--step MM | --layers N | --z a,b,c) [--json] [--out FILE.dat]: Z slices of an STL part.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "rosmill/error.hpp"
#include "rosmill/io/stl.hpp"
#include "rosmill/slice/slicer.hpp"

namespace rosmill::core::cli {
namespace {

struct SliceArgs {
  std::string file, units = "mm", z_list, out;
  double step = NAN, accuracy = NAN;
  int layers = 0;
  bool json = false;
};

// "a,b,c" -> numbers; every item must be a whole number.
std::vector<double> parse_z_list(const std::string& text) {
  std::vector<double> z;
  size_t begin = 0;
  while (begin <= text.size()) {
    const size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    char* stop = nullptr;
    const double v = std::strtod(item.c_str(), &stop);
    if (item.empty() || *stop != '\0' || !std::isfinite(v)) throw Error("--z", "'" + item + "' is not a number");
    z.push_back(v);
    begin = end + 1;
  }
  return planes_from_list(z);
}

std::vector<double> planes_for(const Mesh& mesh, const SliceArgs& a) {
  const int given = !std::isnan(a.step) + (a.layers != 0) + !a.z_list.empty() + !std::isnan(a.accuracy);
  if (given != 1) throw Error("slice", "give exactly one of --step, --layers, --z or --accuracy");
  if (!std::isnan(a.step)) return planes_by_step(mesh, a.step);
  if (a.layers != 0) return planes_by_count(mesh, a.layers);
  if (!std::isnan(a.accuracy)) return planes_by_accuracy(mesh, a.accuracy);
  return parse_z_list(a.z_list);
}

nlohmann::ordered_json to_json(const std::vector<SliceLayer>& layers, double seconds) {
  const SliceSummary s = summarize(layers);
  nlohmann::ordered_json detail = nlohmann::ordered_json::array();
  for (const SliceLayer& l : layers) {
    nlohmann::ordered_json contours = nlohmann::ordered_json::array();
    for (const Contour& c : l.contours)
      contours.push_back({{"points", c.points.size()}, {"closed", c.closed}, {"hole", c.hole}, {"area", c.area},
                          {"parent", c.parent}});
    detail.push_back({{"z", l.z}, {"flat_area", l.flat_area}, {"contours", std::move(contours)}});
  }
  return {{"layers", s.layers}, {"contours", s.contours}, {"open_contours", s.open_contours}, {"points", s.points},
          {"seconds", seconds}, {"layers_detail", std::move(detail)}};
}

void print_text(const std::vector<SliceLayer>& layers, double seconds) {
  const SliceSummary s = summarize(layers);
  std::printf("layers %zu  contours %zu  open %zu  points %zu  seconds %.4f\n", s.layers, s.contours,
              s.open_contours, s.points, seconds);
  for (const SliceLayer& l : layers) {
    size_t holes = 0, open = 0;
    for (const Contour& c : l.contours) holes += c.hole, open += !c.closed;
    std::printf("z %.6f  contours %zu  holes %zu  open %zu  flat_area %.3f\n", l.z, l.contours.size(), holes, open,
                l.flat_area);
  }
}

void run(const SliceArgs& a) {
  StlReadOptions options;
  options.units = parse_units(a.units, "--units");
  const Mesh mesh = read_stl(a.file, options);
  const std::vector<double> planes = planes_for(mesh, a);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<SliceLayer> layers = slice_mesh(mesh, planes);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!a.out.empty()) write_slices_dat(a.out, layers);
  if (a.json)
    std::printf("%s\n", to_json(layers, seconds).dump().c_str());
  else
    print_text(layers, seconds);
}

CommandRegistration reg([](CLI::App& app) {
  auto* cmd = app.add_subcommand("slice", "Z slices of an STL part into closed, nested contours");
  auto a = std::make_shared<SliceArgs>();
  cmd->add_option("FILE", a->file, "STL file (.stl, .stl.gz)")->required();
  cmd->add_option("--step", a->step, "distance between planes (mm), from Zmin + step up to Zmax");
  cmd->add_option("--layers", a->layers, "number of planes evenly spaced strictly between Zmin and Zmax");
  cmd->add_option("--z", a->z_list, "explicit plane heights, comma separated (mm)");
  cmd->add_option("--accuracy", a->accuracy, "largest distance between planes, Zmin and Zmax included (mm)");
  cmd->add_option("--units", a->units, "units of the STL file: mm, inch or m (default mm)");
  cmd->add_flag("--json", a->json, "one JSON object on stdout");
  cmd->add_option("--out", a->out, "write the contours as a .dat file (x y z per line, blank line between contours)");
  cmd->callback([a] { run(*a); });
});

}  // namespace
}  // namespace rosmill::core::cli
