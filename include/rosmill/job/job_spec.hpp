// A job as a YAML file describes it: the part, the raw stock, and the operations in machining order. Every field
// is checked when the file is read; a bad one is an Error naming the file, its line and the field.
//
//   part: cube.stl            # STL (relative to the job file's folder) or primitive:NAME
//   units: mm                 # what the part's (and a stock mesh's) numbers are: mm, inch or m
//   resolution: 0.5           # the stock's cell in mm
//   rapid_feed: 5000          # mm/min, for the time estimate
//   stock: {box: {margin: 5}} # or {mesh: cast.stl} or {cloud: scan.pcd, table_z: 0, units: m}
//   operations:
//     - {name: rough, strategy: rough, tool: flat:10, stepover: 4, stepdown: 2.5, allowance: 0.5, setup: +Z}
//     - {name: rest, strategy: raster, tool: ball:3, rest: true, rest_threshold: 0.1}
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "rosmill/units.hpp"

namespace rosmill::core::job {

struct StockSpec {
  enum class Kind { Box, Mesh, Cloud } kind = Kind::Box;
  double margin = 5.0;   // box: the part's bounding box grown by this in x, y and up (mm)
  std::string file;      // mesh or cloud, absolute
  Units units = Units::Millimetre;  // cloud: what its numbers are
  double table_z = 0.0;  // cloud: the table the scanned stock stands on (mm, workpiece frame)
};

struct OperationSpec {
  std::string name;
  std::string strategy;  // a strategy or preset of the planner
  std::string tool;      // a tool id of the tool table, or ball:D, flat:D, bull:D:r
  double stepover = NAN, stepdown = NAN, allowance = 0.0, tolerance = NAN;
  std::string setup = "+Z";
  // Rest machining: only where the stock the operations before left stands above the design by more than the
  // allowance plus rest_threshold (mm).
  bool rest = false;
  double rest_threshold = 0.1;
  int line = 0;          // where it starts in the job file
};

struct JobSpec {
  std::string source;  // the job file
  std::string part;    // absolute path or primitive:NAME
  Units units = Units::Millimetre;
  double resolution = 0.5;
  double rapid_feed = 5000.0;
  StockSpec stock;
  std::vector<OperationSpec> operations;
};

JobSpec read_job(const std::string& path);
// The same from text; `name` stands for the file in errors and `folder` is where relative paths start.
JobSpec parse_job(const std::string& text, const std::string& name, const std::string& folder);

}  // namespace rosmill::core::job
