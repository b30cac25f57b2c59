// A gzip file inflated beside the others, for the benchmarks that time an ASCII file's parsing, not its inflation.
#pragma once
#include <string>

namespace rosmill::core {

// Inflates `gz` into `dir` as its name without ".gz" and returns that path. Throws Error when it cannot be read.
std::string unpacked(const std::string& gz, const std::string& dir);

}  // namespace rosmill::core
