// rviz views of core data, in metres, built by the conversion unit (the nodes only publish them).
#pragma once
#include <std_msgs/ColorRGBA.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/Marker.h>
#include <visualization_msgs/MarkerArray.h>

#include "rosmill/ros/namespaces.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/toolpath/job.hpp"
#include "rosmill/geometry/setup_frame.hpp"

namespace rosmill::edge {

std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f);
// The colour of a move type in every view: rapid red, feed green, plunge blue.
std_msgs::ColorRGBA move_colour(MoveType t);
// A distinct colour per label (golden-ratio hues), for patches.
std_msgs::ColorRGBA label_colour(uint32_t label);
// The colour of a setup (by its index) in every view: the segments it machines, its toolpaths.
std_msgs::ColorRGBA setup_colour(size_t setup);

// A marker with an identity pose and unit scale, ready for points.
visualization_msgs::Marker base_marker(const std_msgs::Header& header, const std::string& ns, int id, int type);
// Appends facet f's corners (m) to a TRIANGLE_LIST; a degenerate facet adds nothing (it has nothing to draw).
void add_facet(visualization_msgs::Marker& triangles, const Mesh& mesh, size_t f);
// A line of text in rviz that begins at `left` (mm) and runs along +x, the right of the bundled rviz view
// (config/rosmill.rviz): rviz centres a text on its position, so the line is padded with spaces to `chars`
// characters and placed half that width further along +x, and its left end stays put whatever it says.
visualization_msgs::Marker text_from_left(const std_msgs::Header& header, const std::string& ns, int id,
                                          const Vec3& left, const std::string& text, double height_mm, size_t chars);
// How wide `chars` characters of text `height_mm` high are at most in rviz (mm).
double text_width_mm(double height_mm, size_t chars);
// A DELETEALL marker: the first of an array that replaces a whole view.
visualization_msgs::Marker delete_all_marker(const std_msgs::Header& header);

// The part's facets coloured by the setup that machines them (facet_setup: an index, -1 for none: grey), one
// TRIANGLE_LIST in namespace "setups".
visualization_msgs::Marker facets_by_setup_marker(const Mesh& part, const std::vector<int>& facet_setup,
                                                  const std_msgs::Header& header);

// The part as one TRIANGLE_LIST in the workpiece frame (grey unless `colour` is given).
visualization_msgs::Marker mesh_marker(const IndexedTriangles& part, const std_msgs::Header& header,
                                       const std::string& ns, const std_msgs::ColorRGBA& colour);

// A job in rviz: one LINE_STRIP per pass in its own namespace "<toolpath index>/<pass name>" so each can be hidden;
// each segment takes the colour of its move type (the vertex is doubled where the type changes, so colours do not
// blend); a CYLINDER for the tool at the toolpath's start. Positions are rotated from the setup frame back into the
// workpiece frame so the path is drawn around the part as it sits. Starts with a DELETEALL so older views vanish.
// `ns_prefix` goes before every namespace (a job's operations: "rough/toolpath0/..."). With `cut_colour`, the feeds
// and plunges take it (a job's setup's colour) and the rapids are grey. A multi-axis pass adds its tool axes, a
// LINE_LIST of strokes up the axis along the path, in "<pass namespace>/axes".
visualization_msgs::MarkerArray toolpath_markers(const Job& job, const SetupFrame& setup,
                                                 const std_msgs::Header& header, const std::string& ns_prefix = "",
                                                 const std_msgs::ColorRGBA* cut_colour = nullptr);

}  // namespace rosmill::edge
