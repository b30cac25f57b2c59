// Job files (YAML) from their text, as `rosmill job` reads them: every field checked, a bad one refused with the
// file, its line and the field. Relative paths start at the example jobs' folder, so seeds that name its data
// files reach past the part and stock checks.
#include "fuzz_support.hpp"
#include "rosmill/job/job_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rosmill;
  fuzz::read_or_refuse([&] {
    const core::job::JobSpec job =
        core::job::parse_job(fuzz::text_of(data, size), "fuzz.yaml", ROSMILL_SOURCE_DIR "/config/jobs");
    fuzz::require(!job.operations.empty(), "a job without operations was accepted");
    fuzz::require(job.resolution > 0 && job.rapid_feed > 0, "a job with a resolution or rapid feed <= 0");
  });
  return 0;
}
