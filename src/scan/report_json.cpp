#include "rosmill/scan/report_json.hpp"

#include <cmath>

namespace rosmill::core::scan {
namespace {

nlohmann::ordered_json deviation_json(const Deviation& d) {
  return {{"mm", d.distance}, {"at", {d.place.x(), d.place.y(), d.place.z()}}};
}

// JSON has no NaN: an estimate that could not be made is null.
nlohmann::ordered_json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; }

}  // namespace

nlohmann::ordered_json matrix_json(const Eigen::Matrix4d& t) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (int i = 0; i < 4; ++i) rows.push_back({t(i, 0), t(i, 1), t(i, 2), t(i, 3)});
  return rows;
}

nlohmann::ordered_json pose_information_json(const PoseInformation& info) {
  const auto direction = [](const PoseDirection& d) {
    return nlohmann::ordered_json{{"name", d.name},
                                  {"kind", d.rotation ? "rotation" : "translation"},
                                  {"axis", {d.axis.x(), d.axis.y(), d.axis.z()}},
                                  {d.rotation ? "sigma_deg" : "sigma_mm", finite_or_null(d.sigma)},
                                  {"surface_information", d.surface_information},
                                  {"outline_information", d.outline_information},
                                  {"weak", d.weak},
                                  {"free", d.free},
                                  {"outline_only", d.outline_only}};
  };
  nlohmann::ordered_json j;
  j["centre"] = {info.centre.x(), info.centre.y(), info.centre.z()};
  j["radius_mm"] = info.radius;
  j["surface_pairs"] = info.surface_pairs;
  j["outline_pairs"] = info.outline_pairs;
  j["max_sigma_mm"] = info.max_sigma;
  j["dofs"] = nlohmann::ordered_json::array();
  for (const PoseDirection& d : info.dofs) j["dofs"].push_back(direction(d));
  j["weak"] = nlohmann::ordered_json::array();
  for (const PoseDirection& d : info.weak) j["weak"].push_back(direction(d));
  return j;
}

nlohmann::ordered_json registration_json(const RegistrationResult& r) {
  nlohmann::ordered_json j;
  j["transform"] = matrix_json(r.transform);
  j["rms"] = r.rms;
  j["inlier_share"] = r.inlier_share;
  j["overlap"] = r.overlap;
  j["ambiguous"] = r.ambiguous;
  j["ambiguity"] = r.ambiguity;
  j["alternatives"] = nlohmann::ordered_json::array();
  for (const auto& a : r.alternatives) j["alternatives"].push_back(matrix_json(a));
  j["translation_sigma_mm"] = finite_or_null(r.translation_sigma);
  j["rotation_sigma_deg"] = finite_or_null(r.rotation_sigma_deg);
  j["degrees_of_freedom"] = pose_information_json(r.information);
  j["candidates"] = r.candidates;
  j["scan_points_used"] = r.scan_points_used;
  j["seconds"] = r.global_seconds + r.fine_seconds;
  return j;
}

nlohmann::ordered_json inspection_json(const InspectionReport& r, double tolerance, bool registered) {
  nlohmann::ordered_json j;
  if (!registered) j["registration"] = registration_json(r.registration);
  j["points"] = r.deviations.size();
  j["mean_mm"] = r.mean;
  j["rms_mm"] = r.rms;
  j["largest_excess"] = deviation_json(r.largest_excess);
  j["largest_deficit"] = deviation_json(r.largest_deficit);
  j["tolerance_mm"] = tolerance;
  j["within_tolerance"] = r.within_tolerance;
  j["above_tolerance"] = r.above_tolerance;
  j["below_tolerance"] = r.below_tolerance;
  j["histogram"] = {{"low_mm", r.histogram_low}, {"bin_mm", r.bin_width}, {"counts", r.histogram}};
  return j;
}

}  // namespace rosmill::core::scan
