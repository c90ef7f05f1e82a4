// camgen: JSON job in, NC program out. Everything lives in camgen_core; this maps the
// process to run_cli.
#include <iostream>

#include "camgen/cli/cli.hpp"

int main(int argc, char** argv) { return camgen::run_cli(argc, argv, std::cin, std::cout, std::cerr); }
