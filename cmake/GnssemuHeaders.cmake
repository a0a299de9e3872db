# SPDX-License-Identifier: Apache-2.0
# Per-module include interfaces: a target sees the headers of the targets it
# links, and no others, so an include that points at a module the target
# does not link fails to compile (the layers are in docs/architecture.md and
# tests/layering/). The project root is never an include directory.
#
# gnssemu_export_headers(<target> <path>...) links each <path> (a folder or a
# single header, relative to the project root) into the target's own staging
# folder <build>/include/<target>/<path> and exports that folder as the
# target's include directory, so "<path>/x.hpp" resolves for the target and
# for everything that links it.
function(gnssemu_export_headers target)
  set(stage "${PROJECT_BINARY_DIR}/include/${target}")
  foreach(path IN LISTS ARGN)
    if(NOT EXISTS "${PROJECT_SOURCE_DIR}/${path}")
      message(FATAL_ERROR "gnssemu_export_headers(${target}): no ${path} in ${PROJECT_SOURCE_DIR}")
    endif()
    get_filename_component(parent "${stage}/${path}" DIRECTORY)
    file(MAKE_DIRECTORY "${parent}")
    file(CREATE_LINK "${PROJECT_SOURCE_DIR}/${path}" "${stage}/${path}" SYMBOLIC)
  endforeach()
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE "${stage}")
  else()
    target_include_directories(${target} PUBLIC "${stage}")
  endif()
endfunction()
