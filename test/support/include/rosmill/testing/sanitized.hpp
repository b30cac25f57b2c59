// How many random cases a test repeats. Under AddressSanitizer (the sanitizer build: clang, every memory access
// checked) planning and registration on whole real models run several to seventy times slower, and the stage runs
// every gtest within CI's budget only with fewer repeats. The sanitizers look for memory errors and undefined
// behaviour on the code paths a case takes: one or two cases per path find what twenty would, while the
// statistical bounds (twenty poses, every model) are the normal build's to check.
#pragma once
#include <cstddef>
#include <vector>

namespace rosmill::testing {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;  // gcc -fsanitize=address
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;  // clang -fsanitize=address
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// `full` cases normally, `sanitized` under the sanitizers.
constexpr int cases(int full, int sanitized) { return kSanitized ? sanitized : full; }

// The brute-force references of the tests search every triangle per sample. They are test code, not what the
// sanitizers are for: under them, every 16th sample is checked (the planner's own code having run whole).
constexpr size_t kReferenceStride = kSanitized ? 16 : 1;

// Keeps every kReferenceStride-th element of `samples` (all of them in the normal build).
template <class T>
void thin_reference_samples(std::vector<T>& samples) {
  if (kReferenceStride == 1) return;
  std::vector<T> kept;
  for (size_t i = 0; i < samples.size(); i += kReferenceStride) kept.push_back(samples[i]);
  samples.swap(kept);
}

}  // namespace rosmill::testing
