# The sanitizer build (cmake -DROSMILL_SANITIZE=ON, clang): the core areas, the rosmill tool and the core gtests
# under AddressSanitizer and UndefinedBehaviorSanitizer, and the fuzz targets (test/fuzz, libFuzzer). No catkin:
# the core has no ROS dependency; the one fuzz target of the ROS edge builds its message headers itself.
# scripts/fuzz and `scripts/test --sanitize` configure it in build-sanitize.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "ROSMILL_SANITIZE needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++-14")
endif()
# Every undefined behaviour stops the program (a test fails, the fuzzer keeps the input) instead of being logged.
set(ROSMILL_SANITIZERS -fsanitize=address,undefined -fno-sanitize-recover=all)
add_compile_options(${ROSMILL_SANITIZERS} -fno-omit-frame-pointer -gline-tables-only)
# fuzzer-no-link: the coverage feedback libFuzzer steers by (edge counters, and a call at every comparison), only in
# the code the fuzz targets read their input with (cmake/fuzz.cmake names it); the sanitizer runtime answers its
# hooks in programs that are not fuzz targets (the gtests, the tool). In the geometric kernels those calls only
# slowed the gtests.
set(ROSMILL_FUZZ_COVERAGE -fsanitize=fuzzer-no-link)
add_link_options(${ROSMILL_SANITIZERS})
# -O2, not the -O1 the sanitizers' manuals suggest at least, and Eigen's own range assertions off (EIGEN_NO_DEBUG):
# at -O1, and with a bounds check in every coefficient read, clang leaves Eigen's small expression templates and
# nanoflann's point accessor as calls, and planning and registration ran 10 to 100 times slower than the normal
# build -- too slow to run every gtest in CI. An access outside a vector is still ASan's to catch; the project's
# own assertions stay on, and frame pointers keep the reports' stacks whole.
set(CMAKE_CXX_FLAGS_RELEASE "-O2")
add_compile_definitions(EIGEN_NO_DEBUG)
