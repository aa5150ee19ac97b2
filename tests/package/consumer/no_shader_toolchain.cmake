# loom_consumer_require_no_shader_toolchain(<target>): stops the configure step when the shader
# toolchain (glslang, SPIRV-Tools, SPIRV-Cross) or the image codec (stb) came with <target>:
# as targets that find_package defined, or anywhere in <target>'s link interface, followed
# through every target it names. Planning a frame graph needs none of them
# (find_package(loom COMPONENTS framegraph); issue 16). toolchain_check/ tests this check both ways.

# Targets the shader compiler's and image codec's find_dependency calls define.
set(_loom_unwanted_targets
  glslang::glslang glslang::SPIRV glslang::glslang-default-resource-limits glslang::OSDependent
  SPIRV-Tools SPIRV-Tools-static SPIRV-Tools-shared SPIRV-Tools-opt
  spirv-cross-core spirv-cross-glsl spirv-cross-reflect spirv-cross-c
  PkgConfig::stb loom::shader_compiler loom::image_io loom::shaders)

# A library name or path that is one of them: glslang*, *spirv*, stb.
function(_loom_is_toolchain_library item out)
  string(TOLOWER "${item}" lower)
  if(lower MATCHES "glslang|spirv|(^|[^a-z0-9])(lib)?stb([^a-z0-9]|$)")
    set(${out} TRUE PARENT_SCOPE)
  else()
    set(${out} FALSE PARENT_SCOPE)
  endif()
endfunction()

function(loom_consumer_require_no_shader_toolchain target)
  foreach(unwanted IN LISTS _loom_unwanted_targets)
    if(TARGET ${unwanted})
      message(FATAL_ERROR "${target}: the shader toolchain came with it (target ${unwanted} is defined)")
    endif()
  endforeach()
  # Breadth-first over the link interface; $<LINK_ONLY:x> (a static library's private
  # dependency) is still linked, so it counts.
  set(pending ${target})
  set(seen "")
  while(pending)
    list(POP_FRONT pending current)
    if(current IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${current})
    _loom_is_toolchain_library("${current}" bad)
    if(bad)
      message(FATAL_ERROR "${target}: links ${current} (seen through: ${seen})")
    endif()
    if(NOT TARGET ${current})
      continue()
    endif()
    get_target_property(links ${current} INTERFACE_LINK_LIBRARIES)
    if(NOT links)
      set(links "")
    endif()
    foreach(link IN LISTS links)
      string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" link "${link}")
      list(APPEND pending ${link})
    endforeach()
  endwhile()
  message(STATUS "${target} brings no shader toolchain and no stb (checked: ${seen})")
endfunction()
