# The fuzz targets (sanitizer build only): test/fuzz/fuzz_<name>.cpp becomes build-sanitize/fuzz/fuzz_<name>,
# linked with libFuzzer and the areas its reader lives in. Seeds are in test/fuzz/corpus/<name>/, dictionaries
# in test/fuzz/<name>.dict; scripts/fuzz runs them. The target `rosmill_fuzz` builds them all.
# In `scripts/test --sanitize` (and CI) each target also runs for a short fixed time from its seeds, as a test.
add_custom_target(rosmill_fuzz)
set(ROSMILL_FUZZ_TEST_SECONDS 6 CACHE STRING "seconds each fuzz target runs as a test")
# The areas whose code reads the fuzzed inputs (files, tables, programs, controller replies), and the reader of
# the verifier, carry libFuzzer's coverage feedback (cmake/sanitize.cmake). clang refuses a precompiled header
# made without it, so they compile without one.
foreach(area io yaml cutter fixture toolpath machine gcode control planner job)
  target_compile_options(rosmill_${area} PRIVATE ${ROSMILL_FUZZ_COVERAGE})
  set_target_properties(rosmill_${area} PROPERTIES DISABLE_PRECOMPILE_HEADERS ON)
endforeach()
# The meshes and placements the readers build (not the geometric kernels beside them).
set_source_files_properties(src/geometry/input_file.cpp src/geometry/mesh.cpp src/geometry/mesh_report.cpp
  src/geometry/placement.cpp src/geometry/rigid_transform.cpp src/geometry/setup_frame.cpp src/geometry/units.cpp
  src/geometry/value_range.cpp src/geometry/vertex_welder.cpp src/verify/gcode_reader.cpp
  PROPERTIES COMPILE_OPTIONS "${ROSMILL_FUZZ_COVERAGE}" SKIP_PRECOMPILE_HEADERS ON)

function(rosmill_fuzz_target name)
  add_executable(fuzz_${name} test/fuzz/fuzz_${name}.cpp ${ARGN})
  target_compile_options(fuzz_${name} PRIVATE ${ROSMILL_FUZZ_COVERAGE})
  set_target_properties(fuzz_${name} PROPERTIES DISABLE_PRECOMPILE_HEADERS ON)
  target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  target_compile_definitions(fuzz_${name} PRIVATE ROSMILL_SOURCE_DIR="${CMAKE_CURRENT_SOURCE_DIR}")
  set_target_properties(fuzz_${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  add_dependencies(rosmill_fuzz fuzz_${name})
  add_test(NAME fuzz_${name} COMMAND ${CMAKE_COMMAND} -E env ROSMILL_FUZZ_NO_BUILD=1
    ROSMILL_BUILD_DIR=${CMAKE_BINARY_DIR}
    ${CMAKE_CURRENT_SOURCE_DIR}/scripts/fuzz ${name} ${ROSMILL_FUZZ_TEST_SECONDS})
  set_tests_properties(fuzz_${name} PROPERTIES TIMEOUT 300)
endfunction()

rosmill_fuzz_target(stl_ascii)
rosmill_fuzz_target(stl_binary)
rosmill_fuzz_target(cloud)
rosmill_fuzz_target(gcode)
rosmill_fuzz_target(toolpath_json)
rosmill_fuzz_target(job_yaml)
rosmill_fuzz_target(tables)
rosmill_fuzz_target(grbl)
rosmill_fuzz_target(linuxcnc)
target_link_libraries(fuzz_stl_ascii PRIVATE rosmill_io)
target_link_libraries(fuzz_stl_binary PRIVATE rosmill_io)
target_link_libraries(fuzz_cloud PRIVATE rosmill_io)
target_link_libraries(fuzz_gcode PRIVATE rosmill_gcode rosmill_verify)
target_link_libraries(fuzz_toolpath_json PRIVATE rosmill_toolpath)
target_link_libraries(fuzz_job_yaml PRIVATE rosmill_job)
target_link_libraries(fuzz_tables PRIVATE rosmill_cutter rosmill_planner rosmill_gcode)
target_link_libraries(fuzz_grbl PRIVATE rosmill_control)
target_link_libraries(fuzz_linuxcnc PRIVATE rosmill_control)

# The ROS edge without catkin: the package's message headers generated here by gencpp (as catkin would), the
# conversions compiled into the target, the Debian ROS headers and the one ROS library they call (rostime).
find_program(ROSMILL_GENCPP gen_cpp.py PATHS /usr/lib/gencpp /opt/ros/noetic/lib/gencpp NO_DEFAULT_PATH REQUIRED)
find_path(ROSMILL_ROS_SHARE std_msgs/msg/Header.msg PATHS /usr/share /opt/ros/noetic/share REQUIRED)
find_path(ROSMILL_GENCPP_TEMPLATES msg.h.template PATHS /usr/share/gencpp /opt/ros/noetic/share/gencpp REQUIRED)
find_library(ROSMILL_ROSTIME rostime REQUIRED)
set(generated ${CMAKE_BINARY_DIR}/ros_messages)
file(GLOB ROSMILL_MSG_FILES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/msg/*.msg)
# CellRun embeds the actions' results, which only catkin's action generation writes; nothing fuzzed reads it.
list(FILTER ROSMILL_MSG_FILES EXCLUDE REGEX "/CellRun\\.msg$")
set(message_headers "")
foreach(msg_file ${ROSMILL_MSG_FILES})
  get_filename_component(msg_name ${msg_file} NAME_WE)
  add_custom_command(OUTPUT ${generated}/rosmill/${msg_name}.h
    COMMAND /usr/bin/python3 ${ROSMILL_GENCPP} ${msg_file} -p rosmill -o ${generated}/rosmill
      -e ${ROSMILL_GENCPP_TEMPLATES} -Irosmill:${CMAKE_CURRENT_SOURCE_DIR}/msg
      -Istd_msgs:${ROSMILL_ROS_SHARE}/std_msgs/msg -Igeometry_msgs:${ROSMILL_ROS_SHARE}/geometry_msgs/msg
    DEPENDS ${msg_file} ${ROSMILL_MSG_FILES} VERBATIM)
  list(APPEND message_headers ${generated}/rosmill/${msg_name}.h)
endforeach()
rosmill_fuzz_target(ros_convert src/ros/convert.cpp ${message_headers})
target_include_directories(fuzz_ros_convert PRIVATE include ${generated})
target_link_libraries(fuzz_ros_convert PRIVATE rosmill_gcode rosmill_plan rosmill_segment rosmill_toolpath ${ROSMILL_ROSTIME})

