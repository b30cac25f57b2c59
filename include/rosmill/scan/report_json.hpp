// The registration and inspection reports as JSON, the same for `rosmill register/inspect --json` and for the
// report_json of the scan_registrar node's services: millimetres, transforms as 4 rows of 4 numbers.
#pragma once
#include <nlohmann/json.hpp>

#include "rosmill/scan/design_registration.hpp"
#include "rosmill/scan/inspection.hpp"

namespace rosmill::core::scan {

nlohmann::ordered_json matrix_json(const Eigen::Matrix4d& t);
// Per degree of freedom: name, axis, sigma (null when free), information, weak; and the weak directions.
nlohmann::ordered_json pose_information_json(const PoseInformation& info);
nlohmann::ordered_json registration_json(const RegistrationResult& r);
// `registered`: the scan came in the design's frame (no registration to report).
nlohmann::ordered_json inspection_json(const InspectionReport& r, double tolerance, bool registered);

}  // namespace rosmill::core::scan
