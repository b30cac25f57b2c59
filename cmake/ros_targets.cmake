# The ROS layer: one conversion library (src/ros/), one executable per node (src/nodes/*.cpp), the rostest
# nodes and launch files (test/ros/), and the ROS benchmark (bench/ros/). ROS headers stay out of rosmill_core.

# --- rosmill_ros: the one place where core values become messages (mm <-> m).
file(GLOB ROSMILL_ROS_SOURCES CONFIGURE_DEPENDS src/ros/*.cpp)
add_library(rosmill_ros STATIC ${ROSMILL_ROS_SOURCES})
target_include_directories(rosmill_ros PUBLIC include ${CATKIN_DEVEL_PREFIX}/include SYSTEM ${catkin_INCLUDE_DIRS})
target_link_libraries(rosmill_ros PUBLIC rosmill_core ${catkin_LIBRARIES})
add_dependencies(rosmill_ros ${PROJECT_NAME}_generate_messages_cpp)

# --- nodes: src/nodes/<name>.cpp becomes devel/lib/rosmill/<name> (what rosrun and launch files find).
# A node that wraps a capability still on its way to main is built once its core sources exist (keeps every
# commit green while the capabilities land).
set(ROSMILL_NODE_NEEDS_stl_loader src/io/stl*.cpp)
set(ROSMILL_NODE_NEEDS_segmenter src/segment/*.cpp)
set(ROSMILL_NODE_NEEDS_slicer src/slice/*.cpp)
set(ROSMILL_NODE_NEEDS_gcode_bridge src/gcode/*.cpp src/control/*.cpp)
set(ROSMILL_NODES "")
file(GLOB ROSMILL_NODE_SOURCES CONFIGURE_DEPENDS src/nodes/*.cpp)
foreach(node_source ${ROSMILL_NODE_SOURCES})
  get_filename_component(node_name ${node_source} NAME_WE)
  set(node_ready TRUE)
  foreach(pattern ${ROSMILL_NODE_NEEDS_${node_name}})
    file(GLOB node_core_sources CONFIGURE_DEPENDS ${pattern})
    if(NOT node_core_sources)
      message(STATUS "rosmill: node ${node_name} waits for ${pattern} in the core; not built")
      set(node_ready FALSE)
    endif()
  endforeach()
  if(NOT node_ready)
    continue()
  endif()
  list(APPEND ROSMILL_NODES ${node_name})
  add_executable(${node_name} ${node_source})
  target_link_libraries(${node_name} PRIVATE rosmill_ros)
  set_target_properties(${node_name} PROPERTIES
    RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
endforeach()
# cell_checker is a test node a cell's own rostest runs (test/templates/): gtest inside, installed with the nodes.
target_link_libraries(cell_checker PRIVATE GTest::gtest)

# --- rostest: test/ros/*.cpp are test nodes (gtest inside a ROS graph), test/ros/*.test the launch files that
# start the nodes under test with them. catkin registers each .test as a ctest test (_ctest_rosmill_rostest_...),
# run through catkin's wrapper, whose exit code is the test result.
if(CATKIN_ENABLE_TESTING)
  file(GLOB ROSMILL_ROSTEST_NODES CONFIGURE_DEPENDS test/ros/*.cpp)
  foreach(test_source ${ROSMILL_ROSTEST_NODES})
    get_filename_component(test_name ${test_source} NAME_WE)
    add_executable(${test_name} ${test_source})
    rosmill_test_program(${test_name})
    target_link_libraries(${test_name} PRIVATE rosmill_ros rosmill_test_support GTest::gtest)
    target_compile_definitions(${test_name} PRIVATE ${ROSMILL_TEST_DEFS})
    add_dependencies(${test_name} rosmill_cli)  # some run `rosmill` (ROSMILL_CLI) to compare with the nodes
    set_target_properties(${test_name} PROPERTIES
      RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})
  endforeach()
  file(GLOB ROSMILL_ROSTESTS CONFIGURE_DEPENDS test/ros/*.test)
  foreach(rostest_file ${ROSMILL_ROSTESTS})
    add_rostest(${rostest_file})
  endforeach()
  # rosrun finds the nodes of the build (through the devel/ link scripts/build makes beside build/).
  if(CATKIN_DEVEL_PREFIX STREQUAL "${CMAKE_CURRENT_SOURCE_DIR}/build/devel")
    add_test(NAME rosrun_finds_nodes COMMAND rosrun --prefix echo rosmill toolpath_planner)
    set_tests_properties(rosrun_finds_nodes PROPERTIES
      PASS_REGULAR_EXPRESSION "/devel/lib/rosmill/toolpath_planner" FAIL_REGULAR_EXPRESSION "Couldn't find")
  endif()
  # Recordings of a cell made for the replay's tests (test/ros/make_cell_recording.py: the stepped block on the
  # table, three views), each replayed by test/ros/replay/recording.test with what it must give.
  set(ROSMILL_REPLAY_BAGS ${CMAKE_BINARY_DIR}/replay_bags)
  set(replay_part ${CMAKE_CURRENT_SOURCE_DIR}/test/data/parts/stepped_block.stl)
  set(replay_maker ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/make_cell_recording.py)
  set(replay_bag_files "")
  foreach(recording
      "plain" "bz2|--compression;bz2" "lz4|--compression;lz4" "no_tf|--tf;none" "late_tf|--tf-late;0.5"
      "too_late_tf|--tf-late;3" "other_frame|--cloud-frame;camera_link" "several|--repeat;2" "no_scan|--views;0")
    string(REPLACE "|" ";" fields "${recording}")
    list(POP_FRONT fields name)
    add_custom_command(OUTPUT ${ROSMILL_REPLAY_BAGS}/${name}.bag
      COMMAND ${CMAKE_COMMAND} -E make_directory ${ROSMILL_REPLAY_BAGS}
      COMMAND /usr/bin/python3 ${replay_maker} ${replay_part} ${ROSMILL_REPLAY_BAGS}/${name}.bag ${fields}
      DEPENDS ${replay_maker} ${replay_part} VERBATIM)
    list(APPEND replay_bag_files ${ROSMILL_REPLAY_BAGS}/${name}.bag)
  endforeach()
  add_custom_target(replay_bags DEPENDS ${replay_bag_files})
  add_dependencies(tests replay_bags)
  # expect_message: words (joined by +) the reason must hold. `name`: the test's own, so that cases run side by side
  # (ctest -j) do not write one results file (rosunit names it after the test).
  set(replay_test test/ros/replay/recording.test)
  add_rostest(${replay_test} ARGS name:=replay_bz2 case:=bz2 expect_views:=3)
  add_rostest(${replay_test} ARGS name:=replay_lz4 case:=lz4 expect_views:=3)
  add_rostest(${replay_test} ARGS name:=replay_several case:=several expect_views:=6)
  add_rostest(${replay_test} ARGS name:=replay_plain_loop case:=plain loop:=true views:=3 expect_views:=3)
  add_rostest(${replay_test} ARGS name:=replay_late_tf case:=late_tf expect_views:=3)
  add_rostest(${replay_test} ARGS name:=replay_too_late_tf case:=too_late_tf expect_done:=false expect_step:=fusion
    expect_message:=no+transform+scanner+table)
  add_rostest(${replay_test} ARGS name:=replay_no_tf case:=no_tf expect_done:=false expect_step:=fusion
    expect_message:=no+transform+scanner+table)
  add_rostest(${replay_test} ARGS name:=replay_other_frame case:=other_frame expect_done:=false expect_step:=fusion
    expect_message:=no+transform+camera_link+table)
  add_rostest(${replay_test} ARGS name:=replay_other_frame_named case:=other_frame sensor_frame:=scanner
    expect_views:=3)
  add_rostest(${replay_test} ARGS name:=replay_no_scan case:=no_scan first_view_timeout:=5 expect_done:=false
    expect_step:=views expect_message:=nothing+publishes+/scan/points)
  # The template a cell copies (test/templates/), on the plain recording with the bundled job: the whole pipeline.
  # The recording's tf is exact: its scans fused where tf puts them (README: the fusion's ICP moves them).
  add_rostest(test/templates/cell_recording.test ARGS bag:=${ROSMILL_REPLAY_BAGS}/plain.bag
    design:=${replay_part} job:=${CMAKE_CURRENT_SOURCE_DIR}/test/data/jobs/replay_block.yaml refine_views:=false)
  # The template as a cell uses it: from a new package in a workspace of its own, by catkin_make run_tests.
  add_test(NAME cell_package_template COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/install/cell_package.sh
    ${CMAKE_BINARY_DIR} ${ROSMILL_REPLAY_BAGS}/plain.bag ${replay_part}
    ${CMAKE_CURRENT_SOURCE_DIR}/test/data/jobs/replay_block.yaml)
  set_tests_properties(cell_package_template PROPERTIES TIMEOUT 600)
  get_property(rosmill_all_tests DIRECTORY PROPERTY TESTS)
  foreach(t ${rosmill_all_tests})
    if(t MATCHES "^_ctest_rosmill_rostest_")
      # Node output reaches the log at once; results and logs stay in the build folder; localhost resolves.
      set_tests_properties(${t} PROPERTIES TIMEOUT 180 ENVIRONMENT
        "ROS_HOME=${CMAKE_BINARY_DIR}/ros_home;ROS_HOSTNAME=localhost;ROSCONSOLE_STDOUT_LINE_BUFFERED=1;ROS_LOG_DIR=${CMAKE_BINARY_DIR}/ros_home/log;ROSMILL_REPLAY_BAGS=${ROSMILL_REPLAY_BAGS}")
    endif()
    # Only one LinuxCNC runs per machine: tests that start the simulator take the lock "linuxcnc" (tests of other
    # areas that use it should take the same lock) and may wait for another simulator to end.
    if(t MATCHES "^_ctest_rosmill_rostest_.*bridge")
      set_tests_properties(${t} PROPERTIES RESOURCE_LOCK linuxcnc TIMEOUT 300)
    endif()
  endforeach()
endif()

# --- benchmark: bench/ros/*.cpp, ROS programs (bench/*.cpp links only the core).
file(GLOB ROSMILL_ROS_BENCHES CONFIGURE_DEPENDS bench/ros/*.cpp)
foreach(bench_source ${ROSMILL_ROS_BENCHES})
  get_filename_component(bench_name ${bench_source} NAME_WE)
  add_executable(bench_ros_${bench_name} ${bench_source})
  rosmill_bench_program(bench_ros_${bench_name})
  set_target_properties(bench_ros_${bench_name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
  target_link_libraries(bench_ros_${bench_name} PRIVATE rosmill_ros rosmill_test_support)
  # The benchmark starts the node executables itself (with its own master).
  target_compile_definitions(bench_ros_${bench_name} PRIVATE ${ROSMILL_TEST_DEFS}
    ROSMILL_NODE_DIR="${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION}")
  add_dependencies(bench_ros_${bench_name} ${ROSMILL_NODES})
endforeach()

# --- plain gtests of the ROS layer (no master): test/ros/unit/*.cpp, one executable each.
file(GLOB ROSMILL_ROS_UNIT_TESTS CONFIGURE_DEPENDS test/ros/unit/*.cpp)
foreach(test_source ${ROSMILL_ROS_UNIT_TESTS})
  get_filename_component(test_name ${test_source} NAME_WE)
  add_executable(${test_name} ${test_source})
  rosmill_test_program(${test_name})
  list(APPEND ROSMILL_GTEST_TARGETS ${test_name})
  target_link_libraries(${test_name} PRIVATE rosmill_ros GTest::gtest GTest::gtest_main)
  target_include_directories(${test_name} PRIVATE test/core)  # error_of.hpp
  gtest_discover_tests(${test_name} DISCOVERY_TIMEOUT 60)
endforeach()
