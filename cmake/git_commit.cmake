# SPDX-License-Identifier: Apache-2.0
# Writes OUTPUT: the git commit of SOURCE_DIR as a C string literal, e.g.
# "1a2b3c4d5e6f" ("-dirty" appended when tracked files differ from it), for
# daemon/service/build_info.cpp. Run at every build, rewrites OUTPUT only when it
# changes (then only build_info.cpp recompiles):
#   cmake -DSOURCE_DIR=... -DOUTPUT=... [-DOVERRIDE=hash] -P git_commit.cmake
# The commit, in order: OVERRIDE (GNSSEMU_GIT_COMMIT, for packagers building
# from an unpacked source); git, when SOURCE_DIR is the top of a git work tree
# (not a folder inside some other repository); cmake/git_commit.txt, which
# `git archive` fills in (export-subst in .gitattributes); else "unknown".
set(commit "")
if(OVERRIDE)
  set(commit "${OVERRIDE}")
endif()
if(commit STREQUAL "")
  find_program(GIT git)
  if(GIT)
    execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" rev-parse --show-toplevel
      OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc ERROR_QUIET)
    if(rc EQUAL 0)
      file(REAL_PATH "${top}" top)
      file(REAL_PATH "${SOURCE_DIR}" src)
    endif()
    if(rc EQUAL 0 AND top STREQUAL src)
      execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" rev-parse --short=12 HEAD
        OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc ERROR_QUIET)
      if(rc EQUAL 0 AND head MATCHES "^[0-9a-f]+$")
        set(commit "${head}")
        # Tracked files only: the build folder and other untracked files do not count.
        execute_process(COMMAND "${GIT}" -C "${SOURCE_DIR}" status --porcelain --untracked-files=no
          OUTPUT_VARIABLE changes RESULT_VARIABLE rc ERROR_QUIET)
        if(rc EQUAL 0 AND NOT changes STREQUAL "")
          string(APPEND commit "-dirty")
        endif()
      endif()
    endif()
  endif()
endif()
if(commit STREQUAL "" AND EXISTS "${SOURCE_DIR}/cmake/git_commit.txt")
  file(STRINGS "${SOURCE_DIR}/cmake/git_commit.txt" archived LIMIT_COUNT 1)
  if(archived MATCHES "^[0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f]")
    string(SUBSTRING "${archived}" 0 12 commit)
  endif()
endif()
if(commit STREQUAL "")
  set(commit "unknown")
endif()
if(NOT commit MATCHES "^[0-9A-Za-z._+-]+$")
  message(FATAL_ERROR "git_commit.cmake: '${commit}' is not a commit id (GNSSEMU_GIT_COMMIT?)")
endif()
file(WRITE "${OUTPUT}.tmp" "\"${commit}\"\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
