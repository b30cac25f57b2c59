// The setup fields of a job file: a direction, a datum, a fixture. Private to the job area (job_spec.cpp).
#pragma once
#include <string>

#include "job_files.hpp"
#include "rosmill/job/job_spec.hpp"

namespace rosmill::core::job {

// `key` as a tool direction: +Z, -X, ... or [x, y, z] (normalised); `name` gets "+Z"-style or "custom".
Vec3 read_direction(const Fields& f, const std::string& key, std::string& name);
Datum read_datum(const Fields& f, const std::string& key, Datum fallback);
// `table` (the stock on the table, nothing around it), {vise: {...}}, {parallels: {...}, clamps: ...} or
// {boxes: [...], seat: MM}.
fixture::FixtureSpec read_fixture(const YAML::Node& node, const std::string& file, const std::string& place);

}  // namespace rosmill::core::job
