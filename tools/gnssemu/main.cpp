// SPDX-License-Identifier: Apache-2.0
#include <iostream>

#include "tools/gnssemu/cli.hpp"

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  return gnssemu::cli::run_cli(argc, argv, std::cout, std::cerr);
}
