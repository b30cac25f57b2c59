// ASCII STL from memory, as a user's file would be read (see fuzz_stl.hpp).
#include "fuzz_stl.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rosmill::fuzz::read_stl_checked(data, size);
  return 0;
}
