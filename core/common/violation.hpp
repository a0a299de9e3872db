// SPDX-License-Identifier: Apache-2.0
#pragma once
// Violation: a broken cross-field rule of one settings struct, what its
// ...Ranges cannot say (e.g. lose_dbhz <= acquire_dbhz). Each rule is one
// check_* function next to the struct it constrains: the core validator
// throws its reason, and the config layer reports it at the line of the key
// it names, so both read the same rule.
#include <string>
#include <string_view>

namespace gnssemu {

struct Violation {
  std::string_view field;  ///< the setting at fault, as its config key is spelled ("lose_dbhz")
  std::string_view other;  ///< the setting to point at when field is not given; "" for none
  std::string reason;      ///< what is wrong, without a prefix ("lose_dbhz 30 exceeds acquire_dbhz 28 (...)")
};

}  // namespace gnssemu
