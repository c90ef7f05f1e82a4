// Runs the fuzz targets over the committed corpus (tests/fuzz/corpus/<target>/) and every input
// that once failed (tests/fuzz/regressions/<target>/), in every build: a finding fixed stays
// fixed.
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

// Runs `target` over every file under tests/fuzz/<kind>/<name>/; returns how many it ran.
int run_all(const std::string& name, Target target) {
    int count = 0;
    for (const char* kind : {"corpus", "regressions"}) {
        const std::filesystem::path dir = std::filesystem::path(CAMGEN_SOURCE_DIR "/tests/fuzz") / kind / name;
        if (!std::filesystem::exists(dir)) continue;
        for (const auto& e : std::filesystem::directory_iterator(dir)) {
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

TEST_CASE("fuzz corpus and regressions: jobs") { CHECK(run_all("job", camgen::fuzz::job_input) > 0); }
TEST_CASE("fuzz corpus and regressions: programs") { CHECK(run_all("program", camgen::fuzz::program_input) > 0); }
TEST_CASE("fuzz corpus and regressions: mutated samples") { CHECK(run_all("mutated", camgen::fuzz::mutated_sample) > 0); }
