// camgen: JSON job in, NC program out. Everything lives in camgen_core; this maps the
// process to run_cli.
#include <iostream>

#include "camgen/cli/cli.hpp"
#include "camgen/cli/output.hpp"

int main(int argc, char** argv) {
    camgen::install_output_signal_handlers();
    return camgen::run_cli(argc, argv, std::cin, std::cout, std::cerr);
}
