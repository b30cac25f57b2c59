# Test and benchmark programs are not part of a workspace build. As catkin packages do, `catkin_make` (and
# catkin_make_isolated, colcon) builds the package alone; the target `tests` builds the test programs and
# `catkin_make run_tests` builds and runs them, leaving JUnit results for `catkin_test_results`. scripts/build builds
# all of it (the package, `tests` and `benches`), and scripts/test runs every test through ctest.
if(NOT TARGET tests)
  add_custom_target(tests)  # catkin makes it when testing is enabled; the sanitizer build has no catkin
endif()
add_custom_target(benches)

# A program built by `tests` only.
function(rosmill_test_program target)
  set_target_properties(${target} PROPERTIES EXCLUDE_FROM_ALL TRUE)
  add_dependencies(tests ${target})
endfunction()

# A program built by `benches` only (bench/run builds them).
function(rosmill_bench_program target)
  set_target_properties(${target} PROPERTIES EXCLUDE_FROM_ALL TRUE)
  add_dependencies(benches ${target})
endfunction()

# `make run_tests` (catkin_make run_tests) runs a core gtest program whole, as catkin_add_gtest would, its JUnit
# file in test_results/rosmill/ (ctest, through scripts/test, runs each of its cases as a test of its own).
function(rosmill_catkin_run_gtest target)
  if(NOT TARGET run_tests OR NOT DEFINED CATKIN_ENV)
    return()
  endif()
  set(results ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/gtest-${target}.xml)
  add_custom_target(run_tests_${PROJECT_NAME}_gtest_${target}
    COMMAND ${CATKIN_ENV} ${PYTHON_EXECUTABLE} ${catkin_EXTRAS_DIR}/test/run_tests.py ${results}
      "$<TARGET_FILE:${target}> --gtest_output=xml:${results}"
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR} VERBATIM)
  add_dependencies(run_tests_${PROJECT_NAME}_gtest_${target} ${target})
  if(TARGET clean_test_results_${PROJECT_NAME})  # the old results go before the new are written
    add_dependencies(run_tests_${PROJECT_NAME}_gtest_${target} clean_test_results_${PROJECT_NAME})
  endif()
  add_dependencies(run_tests run_tests_${PROJECT_NAME}_gtest_${target})
endfunction()
