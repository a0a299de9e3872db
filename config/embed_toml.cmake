# SPDX-License-Identifier: Apache-2.0
# Writes OUTPUT: a .cpp defining gnssemu::config::default_config_text() with
# the contents of INPUT. Run with cmake -DINPUT=... -DOUTPUT=... -P embed_toml.cmake
file(READ "${INPUT}" text)
set(delim "gnssemu_toml")
string(FIND "${text}" ")${delim}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw-string delimiter )${delim}\"")
endif()
file(WRITE "${OUTPUT}.tmp"
  "// Generated from ${INPUT} by config/embed_toml.cmake. Do not edit.\n"
  "#include \"config/config.hpp\"\n\n"
  "namespace gnssemu::config {\n\n"
  "std::string_view default_config_text() {\n"
  "  static constexpr char kText[] = R\"${delim}(${text})${delim}\";\n"
  "  return {kText, sizeof kText - 1};\n"
  "}\n\n"
  "}  // namespace gnssemu::config\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
