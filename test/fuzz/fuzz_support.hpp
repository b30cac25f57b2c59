// What every fuzz target holds a reader to: an input is either read or refused with rosmill's Error, whose
// message names where the input went wrong. Anything else (another exception, a crash, a sanitizer report, a hang)
// is a finding: libFuzzer keeps the input and stops.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>

#include "rosmill/error.hpp"

namespace rosmill::fuzz {

// A failed property of a read result: reported like a crash, so the input is kept.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "rosmill fuzz finding: %s\n", what.c_str());
  std::abort();
}

inline void require(bool holds, const std::string& what) {
  if (!holds) finding(what);
}

// Runs `read`; a refusal must be rosmill's Error with a place and a reason.
template <class Read>
void read_or_refuse(Read&& read) {
  try {
    read();
  } catch (const core::Error& e) {
    require(!std::string(e.what()).empty(), "an Error without a message");
  }
}

inline std::string text_of(const uint8_t* data, size_t size) { return {reinterpret_cast<const char*>(data), size}; }

}  // namespace rosmill::fuzz
