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
  string(REPLACE "file = \"nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz\""
                 "file = \"${_prefix}/share/gnssemu/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz\"" _conf "${_conf}")
  string(REPLACE "path = \"/tmp/gnssemu/gps0\"" "path = \"/run/gnssemu/gps0\"" _conf "${_conf}")
  string(REPLACE "(gpsd /tmp/gnssemu/gps0)" "(gpsd -b /run/gnssemu/gps0)" _conf "${_conf}")
  file(WRITE "${_stage}/gnssemud.toml" "${_conf}")
  file(INSTALL "${_stage}/gnssemud.toml" DESTINATION "${_etc}")
]])

install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/CHANGELOG.md ${PROJECT_SOURCE_DIR}/NOTICE
  DESTINATION ${CMAKE_INSTALL_DOCDIR})  # NOTICE: Apache-2.0 §4(d)
# Debian's machine-readable copyright (the project's license and the
# third-party files the package installs or compiles in).
install(FILES ${PROJECT_SOURCE_DIR}/packaging/copyright DESTINATION ${CMAKE_INSTALL_DOCDIR})
set(GNSSEMU_MAINTAINER "gnssemu maintainers <maintainers@gnssemu.invalid>" CACHE STRING
    "Maintainer of the .deb and its changelog entries: Name <address>")
# gzip -9n (no name or time stamp: a reproducible package): the man pages, and
# the Debian changelog a native package carries, made from CHANGELOG.md.
install(CODE "set(_maintainer \"${GNSSEMU_MAINTAINER}\")\nset(_version \"${PROJECT_VERSION}\")
set(_docdir \"${CMAKE_INSTALL_DOCDIR}\")\nset(_mandir \"${CMAKE_INSTALL_MANDIR}\")")
install(CODE [[
  function(gnssemu_install_gz file dest)
    get_filename_component(_name "${file}" NAME)
    execute_process(COMMAND gzip -9n -c "${file}" OUTPUT_FILE "${_bin}/install-stage/${_name}.gz" RESULT_VARIABLE _rc)
    if(NOT _rc EQUAL 0)
      message(FATAL_ERROR "gzip of ${file} failed")
    endif()
    file(INSTALL "${_bin}/install-stage/${_name}.gz" DESTINATION "${CMAKE_INSTALL_PREFIX}/${dest}")
  endfunction()
  gnssemu_install_gz("${_src}/docs/man/gnssemud.8" "${_mandir}/man8")
  gnssemu_install_gz("${_src}/docs/man/gnssemu.1" "${_mandir}/man1")
  gnssemu_install_gz("${_src}/docs/man/gnssemud.toml.5" "${_mandir}/man5")
  execute_process(COMMAND ${CMAKE_COMMAND} -DCHANGELOG=${_src}/CHANGELOG.md -DVERSION=${_version}
                          -DMAINTAINER=${_maintainer} -DOUTPUT=${_bin}/install-stage/changelog
                          -P ${_src}/cmake/debian_changelog.cmake
                  RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "CHANGELOG.md: no Debian changelog could be made from it")
  endif()
  gnssemu_install_gz("${_bin}/install-stage/changelog" "${_docdir}")
]])
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.md"
  PATTERN images EXCLUDE PATTERN man EXCLUDE)  # no empty folders in the package
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/examples DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.toml")

set(CPACK_PACKAGE_NAME gnssemu)
set(CPACK_PACKAGE_VENDOR "gnssemu")
set(CPACK_PACKAGE_CONTACT "${GNSSEMU_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "GNSS receiver emulator: an emulated u-blox M8 fed by vehicle truth")
set(CPACK_PACKAGE_DESCRIPTION "gnssemud makes a simulated vehicle look like it carries a real GNSS
receiver: from the antenna's true position sent over UDP by a simulator it
computes, in real time, the fix a receiver would report there (real broadcast
ephemerides, atmosphere, buildings, time-correlated errors, faults) and sends
it as NMEA 0183 and UBX, as a u-blox M8 or M9, on a pty, serial, TCP or UDP
port, so gpsd, an autopilot or an ECU reads it unchanged. gnssemu runs the
same receiver offline over files.")
set(CPACK_STRIP_FILES ON)  # the binaries without their symbol tables (debian-policy 10.1)
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
