# Install rules and the CMake package config, so that an outside project can do
#
#   find_package(loom 0.1 REQUIRED COMPONENTS framegraph gl vulkan)
#   target_link_libraries(engine PRIVATE loom::framegraph loom::gl loom::vulkan)
#
# Each library is one component with its own export set (loom-<component>-targets.cmake) and
# the headers under its include/ folder. A component that this build did not make (a backend
# switched off with LOOM_WITH_GL / LOOM_WITH_VULKAN) is not installed and the config reports it
# as not found. The config (cmake/loomConfig.cmake.in) loads what was asked for plus what that
# needs, and finds the third-party packages those static libraries link.
#
#   component        targets                                  needs
#   rhi              loom::rhi                                (nothing third-party)
#   shader_compiler  loom::shader_compiler                    rhi, glslang, SPIRV-Cross
#   image_io         loom::image_io                           rhi, stb (pkg-config)
#   shaders          loom::shaders (+ loom::shaders_embedded) rhi, shader_compiler
#   framegraph       loom::framegraph                         rhi, nlohmann_json
#   gl               loom::gl                                 rhi, epoxy (pkg-config), glfw3
#   vulkan           loom::vulkan                             rhi, Vulkan, glfw3
#   backends         loom::backends (rhi::create_device)      rhi and every backend built
#   passes           loom::passes                             framegraph, shaders, shader_compiler, scene, glm
#   scene            loom::scene                              rhi, glm
#   gltf             loom::gltf                               scene, image_io, tinygltf, nlohmann_json
#   renderer         loom::renderer                           gltf, scene, passes
#
# Targets keep their in-tree names (loom::rhi is the alias of loom_rhi); EXPORT_NAME gives the
# installed ones the same names.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LOOM_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/loom" CACHE STRING
    "Where the CMake package config of loom is installed, relative to the prefix")

# Components in dependency order: the config loads them in this order.
set(LOOM_ALL_COMPONENTS rhi shader_compiler image_io shaders framegraph gl vulkan backends scene passes gltf renderer)

set(LOOM_PACKAGE_COMPONENTS "")
set(LOOM_PACKAGE_COMPONENT_NEEDS "")

# _loom_install_component(<component> TARGETS <target>... [NEEDS <component>...])
# Installs the targets (and the public headers under each one's include/ folder) as one
# export set; skipped when a target does not exist in this build.
macro(_loom_install_component component)
  cmake_parse_arguments(_LIC "" "" "TARGETS;NEEDS" ${ARGN})
  set(_lic_present TRUE)
  foreach(_lic_target IN LISTS _LIC_TARGETS)
    if(NOT TARGET ${_lic_target})
      set(_lic_present FALSE)
    endif()
  endforeach()
  if(_lic_present)
    install(TARGETS ${_LIC_TARGETS}
      EXPORT loom-${component}-targets
      ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
      LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
      RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
      INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    foreach(_lic_target IN LISTS _LIC_TARGETS)
      get_target_property(_lic_source_dir ${_lic_target} SOURCE_DIR)
      if(EXISTS "${_lic_source_dir}/include")
        # C++ headers only (shaders/include also holds the GLSL snippets, embedded in the library).
        install(DIRECTORY "${_lic_source_dir}/include/"
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
      endif()
    endforeach()
    install(EXPORT loom-${component}-targets
      NAMESPACE loom::
      FILE loom-${component}-targets.cmake
      DESTINATION ${LOOM_INSTALL_CMAKEDIR})
    list(APPEND LOOM_PACKAGE_COMPONENTS ${component})
    string(APPEND LOOM_PACKAGE_COMPONENT_NEEDS "set(_loom_needs_${component} \"${_LIC_NEEDS}\")\n")
  endif()
endmacro()

# loom_shaders links the generated table of embedded shaders; as a static library its
# dependency goes with it. Its generated header is needed to build loom only.
if(TARGET loom_shaders_embedded)
  set_target_properties(loom_shaders_embedded PROPERTIES EXPORT_NAME shaders_embedded)
  get_target_property(_loom_embedded_includes loom_shaders_embedded INTERFACE_INCLUDE_DIRECTORIES)
  set_property(TARGET loom_shaders_embedded PROPERTY INTERFACE_INCLUDE_DIRECTORIES
               "$<BUILD_INTERFACE:${_loom_embedded_includes}>")
endif()

set(_loom_backend_components "")
if(TARGET loom_gl)
  list(APPEND _loom_backend_components gl)
endif()
if(TARGET loom_vulkan)
  list(APPEND _loom_backend_components vulkan)
endif()

_loom_install_component(rhi TARGETS loom_rhi)
_loom_install_component(shader_compiler TARGETS loom_shader_compiler NEEDS rhi)
_loom_install_component(image_io TARGETS loom_image_io NEEDS rhi)
_loom_install_component(shaders TARGETS loom_shaders loom_shaders_embedded NEEDS rhi shader_compiler)
_loom_install_component(framegraph TARGETS loom_framegraph NEEDS rhi)
_loom_install_component(gl TARGETS loom_gl NEEDS rhi)
_loom_install_component(vulkan TARGETS loom_vulkan NEEDS rhi)
_loom_install_component(backends TARGETS loom_backends NEEDS rhi ${_loom_backend_components})
_loom_install_component(scene TARGETS loom_scene NEEDS rhi)
_loom_install_component(passes TARGETS loom_passes NEEDS framegraph shaders shader_compiler scene)
_loom_install_component(gltf TARGETS loom_gltf NEEDS scene image_io)
_loom_install_component(renderer TARGETS loom_renderer NEEDS gltf scene passes framegraph)

configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/loomConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/loomConfig.cmake"
  INSTALL_DESTINATION ${LOOM_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API.
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/loomConfigVersion.cmake"
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/loomConfig.cmake" "${PROJECT_BINARY_DIR}/loomConfigVersion.cmake"
  DESTINATION ${LOOM_INSTALL_CMAKEDIR})
