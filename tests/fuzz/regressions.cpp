// Runs the fuzz targets over their seed corpus (the samples for jobs, the golden programs for
// programs, tests/fuzz/corpus/mutated/ for mutations) and every input that once failed
// (tests/fuzz/regressions/<target>/), in every build: a finding fixed stays fixed.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace {

using Target = std::optional<std::string> (*)(const std::uint8_t*, std::size_t);

// Runs `target` over every file of `dirs` (relative to the source folder); returns how many.
int run_all(const std::vector<std::string>& dirs, Target target) {
    int count = 0;
    for (const std::string& d : dirs) {
        const std::filesystem::path dir = std::filesystem::path(CAMGEN_SOURCE_DIR) / d;
        if (!std::filesystem::exists(dir)) continue;
        for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
            if (!e.is_regular_file() || e.path().filename().string().front() == '.') continue;
            std::ifstream in(e.path(), std::ios::binary);
            const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            INFO(e.path().string());
            const auto problem = target(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
            CHECK_MESSAGE(!problem, problem.value_or(""));
            ++count;
        }
    }
    return count;
}

}  // namespace

TEST_CASE("fuzz corpus and regressions: jobs") {
    CHECK(run_all({"samples", "tests/fuzz/regressions/job"}, camgen::fuzz::job_input) > 0);
}
TEST_CASE("fuzz corpus and regressions: programs") {
    CHECK(run_all({"tests/golden", "tests/fuzz/regressions/program"}, camgen::fuzz::program_input) > 0);
}
TEST_CASE("fuzz corpus and regressions: mutated samples") {
    CHECK(run_all({"tests/fuzz/corpus/mutated", "tests/fuzz/regressions/mutated"}, camgen::fuzz::mutated_sample) > 0);
}
