// Toolpath files (what `rosmill plan -o` writes and `rosmill post` and `rosmill verify` read) from their text:
// read or refused naming the field; what is read is written back and read again to the same moves.
#include "fuzz_support.hpp"
#include "rosmill/toolpath/toolpath_io.hpp"

#include <nlohmann/json.hpp>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace rosmill;
  fuzz::read_or_refuse([&] {
    const std::vector<core::Toolpath> job = core::parse_toolpath_text(fuzz::text_of(data, size), "fuzz.json");
    fuzz::require(!job.empty(), "a toolpath file without toolpaths was accepted");
    for (const core::Toolpath& tp : job) {
      const core::Toolpath again = core::toolpath_from_json(core::toolpath_to_json(tp), "written back");
      fuzz::require(again.passes.size() == tp.passes.size(), "a toolpath written back lost passes");
      for (size_t p = 0; p < tp.passes.size(); ++p) {
        fuzz::require(again.passes[p].moves.size() == tp.passes[p].moves.size(), "a pass written back lost moves");
        for (size_t m = 0; m < tp.passes[p].moves.size(); ++m)
          fuzz::require(again.passes[p].moves[m].to == tp.passes[p].moves[m].to, "a move written back moved");
      }
    }
  });
  return 0;
}
