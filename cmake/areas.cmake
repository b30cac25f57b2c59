# The core as one static library per area, each with the areas it builds on declared. An area sees only its own
# headers and those of the areas it declares (each area's include/rosmill/<area> is linked into an include root of
# its own under the build folder), so a file that includes from an area above it does not compile.
# The headers at the top (rosmill/error.hpp, units.hpp, heap_reuse.hpp) are the base every area sees.
#
#   rosmill_area(NAME DEPENDS AREA... [LIBS EXTERNAL...])
set(ROSMILL_AREA_ROOT ${CMAKE_BINARY_DIR}/areas)
file(MAKE_DIRECTORY ${ROSMILL_AREA_ROOT}/base/rosmill)
file(GLOB rosmill_base_headers ${CMAKE_CURRENT_SOURCE_DIR}/include/rosmill/*.hpp)
foreach(header ${rosmill_base_headers})
  get_filename_component(header_name ${header} NAME)
  file(CREATE_LINK ${header} ${ROSMILL_AREA_ROOT}/base/rosmill/${header_name} SYMBOLIC)
endforeach()
add_library(rosmill_base INTERFACE)
target_include_directories(rosmill_base INTERFACE $<BUILD_INTERFACE:${ROSMILL_AREA_ROOT}/base>)

set(ROSMILL_AREAS "")
function(rosmill_area name)
  cmake_parse_arguments(AREA "" "" "DEPENDS;LIBS" ${ARGN})
  set(root ${ROSMILL_AREA_ROOT}/${name})
  file(MAKE_DIRECTORY ${root}/rosmill)
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/include/rosmill/${name} ${root}/rosmill/${name} SYMBOLIC)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/${name}/*.cpp)
  add_library(rosmill_${name} STATIC ${sources})
  target_include_directories(rosmill_${name} PUBLIC $<BUILD_INTERFACE:${root}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src/${name})
  list(TRANSFORM AREA_DEPENDS PREPEND rosmill_ OUTPUT_VARIABLE area_libraries)
  target_link_libraries(rosmill_${name} PUBLIC rosmill_base ${area_libraries} ${AREA_LIBS})
  set(ROSMILL_AREAS ${ROSMILL_AREAS} rosmill_${name} PARENT_SCOPE)
endfunction()
