// camgen: JSON job in, NC program out. Everything lives in camgen_core; this maps the
// process to run_cli.
#include <iostream>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "camgen/cli/cli.hpp"
#include "camgen/cli/output.hpp"

int main(int argc, char** argv) {
#ifdef __GLIBC__
    // Blocks of a megabyte and more (a large job's text, its packed arrays, a profile and the
    // vectors that check it) get pages of their own, given back when freed. glibc's default
    // raises this threshold to 32 MB after the first such block is freed, and the freed
    // blocks of a growing vector then stay in the heap: a million-segment contour peaked at
    // 204 MB instead of 161 MB.
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
    camgen::install_output_signal_handlers();
    return camgen::run_cli(argc, argv, std::cin, std::cout, std::cerr);
}
