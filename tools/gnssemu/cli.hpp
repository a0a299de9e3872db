// SPDX-License-Identifier: Apache-2.0
#pragma once
// The gnssemu command line (docs/cli.md). The executable is a thin main()
// around run_cli(); tests drive run_cli() with string streams.
#include <ostream>

namespace gnssemu::cli {

/// Exit statuses of run_cli().
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;  ///< a file or value was rejected (message on err)
inline constexpr int kExitUsage = 2;     ///< the command line did not parse (CLI11 message on err)

/// Parse argv (argv[0] is the program name) and run the subcommand: CSV on
/// out, messages on err. Never throws.
int run_cli(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

}  // namespace gnssemu::cli
