# What a catkin install ships (`cmake --install build --prefix P`, or catkin's install space): the libraries and
# their headers, the `rosmill` tool, the nodes, the launch files and the configuration (tools, machine, node
# parameters, rviz). Messages, services and actions are installed by catkin's generate_messages().
install(TARGETS ${ROSMILL_LIBRARIES}
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
install(DIRECTORY include/rosmill/ DESTINATION ${CATKIN_PACKAGE_INCLUDE_DESTINATION} FILES_MATCHING PATTERN "*.hpp")
install(TARGETS rosmill_cli rosmill_info rosmill_full RUNTIME DESTINATION ${CATKIN_GLOBAL_BIN_DESTINATION})
install(TARGETS ${ROSMILL_NODES} RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(DIRECTORY launch config DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION})
# The test a cell copies into its own package to replay its recordings (README: Test your cell ...).
install(DIRECTORY test/templates/ DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/templates)

# The install checked as a user meets it: installed into a temporary prefix, then launched from there.
if(CATKIN_ENABLE_TESTING)
  add_test(NAME install_and_launch
    COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/test/install/install_and_launch.sh ${CMAKE_BINARY_DIR})
  set_tests_properties(install_and_launch PROPERTIES TIMEOUT 180)
endif()
