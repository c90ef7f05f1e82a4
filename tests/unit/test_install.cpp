// Where built-in machines come from: the folder installed beside the executable, else the
// compiled-in copies. tests/install/check_install.sh runs an installed camgen for the first;
// here, from the build folder, the second.
#include <doctest/doctest.h>

#include <algorithm>

#include "camgen/post/machine.hpp"
#include "tests/unit/support.hpp"

namespace camgen {
namespace test_install {  // named: a unity build compiles several test files as one

TEST_CASE("install: from the build folder, the built-in machines are the compiled-in copies") {
    // camgen_tests has no ../share/camgen/machines beside it.
    CHECK_FALSE(installed_machine_dir().has_value());
    std::vector<std::string> builtin;
    for (const MachineEntry& e : machine_catalogue())
        if (e.origin == "built-in") {
            CHECK(e.text != nullptr);
            CHECK(e.path.empty());
            builtin.push_back(e.name);
        }
    std::vector<std::string> embedded;
    for (const auto& e : embedded_machines()) embedded.emplace_back(e.name);
    std::sort(embedded.begin(), embedded.end());
    CHECK(builtin == embedded);
    CHECK(load_machine("fanuc").source == "machines/fanuc.json");
}

}  // namespace test_install
}  // namespace camgen
