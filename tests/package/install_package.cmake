# Installs loom's build tree into a fresh prefix (what the package tests build against):
#   cmake -DBUILD_DIR=<loom build> -DPREFIX=<dir> [-DCONFIG=<config>] -P install_package.cmake
file(REMOVE_RECURSE "${PREFIX}")
set(config_args "")
if(CONFIG)
  set(config_args --config "${CONFIG}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}" ${config_args}
                RESULT_VARIABLE result OUTPUT_QUIET)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} failed (${result}); are loom's libraries built?")
endif()
file(GLOB configs "${PREFIX}/*/cmake/loom/loomConfig.cmake" "${PREFIX}/*/*/cmake/loom/loomConfig.cmake")
if(NOT configs)
  message(FATAL_ERROR "no loomConfig.cmake under ${PREFIX}")
endif()
message(STATUS "installed loom into ${PREFIX}")
