# SPDX-License-Identifier: Apache-2.0
# gnssemu_build_info: the release version (project() in CMakeLists.txt, the one
# place it is defined) and the git commit of the source, for `gnssemud
# --version` and `gnssemu version` (daemon/service/build_info.hpp). The commit is
# looked up at every build, not only at configure time, so a build after a new
# commit or checkout names it; cmake/git_commit.cmake says where it comes from.
set(GNSSEMU_GIT_COMMIT "" CACHE STRING
    "Commit to report when the source is not a git checkout (empty: git, then cmake/git_commit.txt, else unknown)")
set(_commit_inc "${PROJECT_BINARY_DIR}/generated/git_commit.inc")
file(MAKE_DIRECTORY "${PROJECT_BINARY_DIR}/generated")
add_custom_target(gnssemu_git_commit
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DOUTPUT=${_commit_inc}
          -DOVERRIDE=${GNSSEMU_GIT_COMMIT} -P ${PROJECT_SOURCE_DIR}/cmake/git_commit.cmake
  BYPRODUCTS ${_commit_inc}
  COMMENT "Git commit of the source"
  VERBATIM)
add_library(gnssemu_build_info STATIC ${PROJECT_SOURCE_DIR}/daemon/service/build_info.cpp)
add_dependencies(gnssemu_build_info gnssemu_git_commit)
target_include_directories(gnssemu_build_info PRIVATE "${PROJECT_BINARY_DIR}/generated")
target_compile_definitions(gnssemu_build_info PRIVATE GNSSEMU_VERSION="${PROJECT_VERSION}")
target_link_libraries(gnssemu_build_info PRIVATE gnssemu_warnings)
gnssemu_export_headers(gnssemu_build_info daemon/service/build_info.hpp)
