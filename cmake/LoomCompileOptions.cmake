include(GNUInstallDirs)

# Warnings for loom's own targets. Third-party headers come in as SYSTEM includes
# (imported targets), so their warnings never fail the build.
function(loom_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                           -Wold-style-cast -Wcast-align -Wnull-dereference -Wimplicit-fallthrough)
    if(LOOM_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
endfunction()

# A loom library: loom_<name> with alias loom::<name>, public headers in include/. Installed
# (cmake/LoomInstall.cmake) it is loom::<name> too.
function(loom_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  add_library(loom_${name} ${ARG_SOURCES})
  add_library(loom::${name} ALIAS loom_${name})
  set_target_properties(loom_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(loom_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  loom_target_defaults(loom_${name})
endfunction()
