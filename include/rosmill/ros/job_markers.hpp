// A job in rviz as it runs: the toolpaths of every operation so far (namespaces "<n>_<operation>/toolpath<t>/...",
// each hideable; a job's setups each in their own colour), each setup's fixture ("fixture/<setup>": a faint fill,
// id 0, and its boxes' edges, id 1, so that the part and its toolpaths show through it), the part's faces coloured
// by the setup that finishes them ("setups"; grey where none does), and the stock after the latest operation as a
// triangle mesh coloured by the material it leaves on the part (the stock's top above the design's, seen from the
// operation's setup), with a legend of the colours; after the job, the faces by the material left on them. All in
// the workpiece frame.
#pragma once
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "rosmill/job/run_job.hpp"
#include "rosmill/ros/namespaces.hpp"

namespace rosmill::edge {

// The colour of `left` mm of material on the part: magenta below the design (a gouge deeper than `tolerance`),
// green within `tolerance` of it, then through yellow to red at `full` mm and above; grey where the stock stands
// over no part (NaN).
std_msgs::ColorRGBA material_left_colour(float left, double tolerance, double full);

// The namespace an operation's toolpaths start with: "<its number from 1>_<its name>/" (names repeat over setups).
std::string operation_namespace(const job::OperationView& view);


class JobMarkers {
 public:
  explicit JobMarkers(std_msgs::Header header) : header_(std::move(header)) {}
  // Adds the operation's toolpaths (and, for its setup's first, the fixture and the faces by setup); returns every
  // operation's so far, starting with a DELETEALL.
  const visualization_msgs::MarkerArray& add_operation(const job::OperationView& view);
  // The stock the operation left, coloured, and the legend beside it (namespaces "stock", "legend").
  visualization_msgs::MarkerArray stock(const job::OperationView& view) const;
  // After the job: the part's faces by what the job left on them ("surface": green within their limit, red above
  // it, grey not to be finished) and a label at each face above its limit ("surface_notes": how much, why); returns
  // every marker so far.
  const visualization_msgs::MarkerArray& add_surface(const Mesh& part, const job::SurfaceAccount& surface);

 private:
  std_msgs::Header header_;
  visualization_msgs::MarkerArray toolpaths_;
  int setups_seen_ = 0;
};

}  // namespace rosmill::edge
