# SPDX-License-Identifier: Apache-2.0
# Truth senders (docs/truth-protocol.md, docs/sitl.md): binary truth from the C++ sender
# through gnssemud to NMEA on a pty, and the CARLA example's self-test.
# Included from tests/integration/CMakeLists.txt, after Python3 is found.
foreach(case static mixed flood)
  add_test(NAME integration.truth_binary.${case}
    COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/truth_binary_integration.py
      --gnssemud $<TARGET_FILE:gnssemud>
      --sender $<TARGET_FILE:send_truth>
      --json-sender ${PROJECT_SOURCE_DIR}/tools/senders/send_truth.py
      --nav ${GNSSEMU_TEST_DATA}/nav/brdc0010.22n
      ${case})
  set_tests_properties(integration.truth_binary.${case} PROPERTIES
    LABELS integration TIMEOUT 90 SKIP_RETURN_CODE 77 RUN_SERIAL TRUE)
endforeach()

# The CARLA frame conversions and record layout, without CARLA.
add_test(NAME senders.carla_truth_self_test
  COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/senders/carla_truth.py --self-test)
set_tests_properties(senders.carla_truth_self_test PROPERTIES LABELS unit TIMEOUT 30)

# Autopilot SITL truth (MAVLink SIM_STATE) through mavlink_truth.py into a
# three-vehicle fleet (docs/sitl.md); the bridge's frame parser on its own.
add_test(NAME integration.truth.sitl_bridge
  COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/sitl_bridge_integration.py
    --gnssemud $<TARGET_FILE:gnssemud>
    --bridge ${PROJECT_SOURCE_DIR}/tools/senders/mavlink_truth.py
    --nav ${PROJECT_SOURCE_DIR}/config/nav/BRDC00IGS_R_20240100000_01D_MN_gnssemu.rnx.gz)
set_tests_properties(integration.truth.sitl_bridge PROPERTIES LABELS integration TIMEOUT 120)
add_test(NAME senders.mavlink_truth_self_test
  COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/senders/mavlink_truth.py --self-test)
set_tests_properties(senders.mavlink_truth_self_test PROPERTIES LABELS unit TIMEOUT 30)
