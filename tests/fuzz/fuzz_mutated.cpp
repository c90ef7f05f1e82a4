// libFuzzer entry point: mutated_sample (see fuzz_targets.hpp). Built with -DCAMGEN_FUZZ=ON and clang.
#include <cstdio>
#include <cstdlib>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (auto problem = camgen::fuzz::mutated_sample(data, size)) {
        std::fprintf(stderr, "camgen fuzz finding: %s\n", problem->c_str());
        std::abort();
    }
    return 0;
}
