// Where a toolpath move is, in words a person can find it by: its number over the whole job (as the stock's
// programs and the verifier number moves, from 1), its toolpath and pass, its kind and its two ends.
#pragma once
#include <cstdint>
#include <string>

#include "rosmill/toolpath/job.hpp"

namespace rosmill::core {

// "move 9596: toolpath 2 (waterline), pass 'z 12.5', a feed from (x, y, z) to (x, y, z)"; "move N" alone when the
// job has no such move.
std::string move_place(const Job& job, uint32_t number);

}  // namespace rosmill::core
