# SPDX-License-Identifier: Apache-2.0
# Install layout of the service and `cpack -G DEB` (docs/daemon.md §Packaging):
# gnssemud, gnssemu, systemd units, /etc/gnssemu/gnssemud.toml, default
# config and nav data, man pages gnssemud(8), gnssemu(1), gnssemud.toml(5).
include(GNUInstallDirs)

# Units and /etc/gnssemu/gnssemud.toml name installed paths: written at
# install time for the prefix in force then (cpack's /usr, or the configured
# one), so one build serves `cmake --install` and the package. Prefix /usr:
# /etc and /lib/systemd/system; another prefix: etc/ and lib/systemd/system under it.
install(CODE "set(_src \"${PROJECT_SOURCE_DIR}\")\nset(_bin \"${PROJECT_BINARY_DIR}\")")
install(CODE [[
  set(_prefix "${CMAKE_INSTALL_PREFIX}")
  if(_prefix STREQUAL "/usr")
    set(_etc "/etc/gnssemu")
    set(_units "/lib/systemd/system")
  else()
    set(_etc "${_prefix}/etc/gnssemu")
    set(_units "${_prefix}/lib/systemd/system")
  endif()
  set(_stage "${_bin}/install-stage")
  file(MAKE_DIRECTORY "${_stage}")
  foreach(_unit gnssemud.service gnssemud@.service)
    file(READ "${_src}/systemd/${_unit}" _text)
    string(REPLACE "/usr/bin/gnssemud" "${_prefix}/bin/gnssemud" _text "${_text}")
    file(WRITE "${_stage}/${_unit}" "${_text}")
    file(INSTALL "${_stage}/${_unit}" DESTINATION "${_units}")
  endforeach()
  # default.toml with the installed nav data and its pty in the unit's RuntimeDirectory.
  file(READ "${_src}/config/default.toml" _conf)
  string(REPLACE "file = \"nav/brdc0010.22n\"" "file = \"${_prefix}/share/gnssemu/nav/brdc0010.22n\"" _conf "${_conf}")
  string(REPLACE "path = \"/tmp/gnssemu/gps0\"" "path = \"/run/gnssemu/gps0\"" _conf "${_conf}")
  string(REPLACE "(gpsd /tmp/gnssemu/gps0)" "(gpsd -b /run/gnssemu/gps0)" _conf "${_conf}")
  file(WRITE "${_stage}/gnssemud.toml" "${_conf}")
  file(INSTALL "${_stage}/gnssemud.toml" DESTINATION "${_etc}")
]])

install(FILES ${PROJECT_SOURCE_DIR}/docs/man/gnssemud.8 DESTINATION ${CMAKE_INSTALL_MANDIR}/man8)
install(FILES ${PROJECT_SOURCE_DIR}/docs/man/gnssemu.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${PROJECT_SOURCE_DIR}/docs/man/gnssemud.toml.5 DESTINATION ${CMAKE_INSTALL_MANDIR}/man5)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/CHANGELOG.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
# Debian's machine-readable copyright (the project's license and the
# third-party files the package installs or compiles in), and the Debian
# changelog a native package carries, made from CHANGELOG.md at install time.
install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright DESTINATION ${CMAKE_INSTALL_DOCDIR})
set(GNSSEMU_MAINTAINER "gnssemu maintainers <maintainers@gnssemu.invalid>" CACHE STRING
    "Maintainer of the .deb and its changelog entries: Name <address>")
install(CODE "set(_maintainer \"${GNSSEMU_MAINTAINER}\")\nset(_version \"${PROJECT_VERSION}\")\nset(_docdir \"${CMAKE_INSTALL_DOCDIR}\")")
install(CODE [[
  execute_process(COMMAND ${CMAKE_COMMAND} -DCHANGELOG=${_src}/CHANGELOG.md -DVERSION=${_version}
                          -DMAINTAINER=${_maintainer} -DOUTPUT=${_bin}/install-stage/changelog
                          -P ${_src}/cmake/debian_changelog.cmake
                  RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "CHANGELOG.md: no Debian changelog could be made from it")
  endif()
  # -n: no name or time stamp in the gzip header, so the package is reproducible.
  execute_process(COMMAND gzip -9nf ${_bin}/install-stage/changelog RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "gzip of the Debian changelog failed")
  endif()
  file(INSTALL ${_bin}/install-stage/changelog.gz DESTINATION "${CMAKE_INSTALL_PREFIX}/${_docdir}")
]])
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/examples DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.toml")

set(CPACK_PACKAGE_NAME gnssemu)
set(CPACK_PACKAGE_VENDOR "gnssemu")
set(CPACK_PACKAGE_CONTACT "${GNSSEMU_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "GNSS receiver emulator: an emulated u-blox M8 fed by vehicle truth")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # dpkg-shlibdeps: libembree, libserialport, libsystemd ...
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "gpsd, gpsd-clients")
# /etc/gnssemu/gnssemud.toml is a conffile: an upgrade keeps the user's edits.
file(WRITE ${PROJECT_BINARY_DIR}/debian/conffiles "/etc/gnssemu/gnssemud.toml\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_BINARY_DIR}/debian/conffiles)
set(CPACK_GENERATOR DEB)
include(CPack)
