// Where built-in machines come from: the folder installed beside the executable, else the
// compiled-in copies (tests/install/check_install.sh runs an installed camgen for the first).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "camgen/post/machine.hpp"
#include "tests/unit/support.hpp"

namespace camgen {
namespace {

TEST_CASE("install: machines_in reads the *.json files of a folder, named by their stems, sorted") {
    const std::filesystem::path dir = test::scratch("install-machines-in");
    std::ofstream(dir / "zeta.json") << "{\"z\": 1}";
    std::ofstream(dir / "alpha.json") << "{\"a\": 1}";
    std::ofstream(dir / "notes.txt") << "not a machine";
    std::filesystem::create_directory(dir / "folder.json");
    const std::vector<BuiltinMachine> machines = machines_in(dir.string());
    REQUIRE(machines.size() == 2);
    CHECK(machines[0].name == "alpha");
    CHECK(machines[0].text == "{\"a\": 1}");
    CHECK(machines[0].source == (dir / "alpha.json").string());
    CHECK(machines[1].name == "zeta");
    CHECK_THROWS_AS(machines_in((dir / "missing").string()), IoError);
}

TEST_CASE("install: from the build folder, the built-in machines are the compiled-in copies") {
    // camgen_tests has no share/camgen/machines beside it.
    const std::vector<BuiltinMachine> machines = builtin_machines();
    REQUIRE(machines.size() == embedded_machines().size());
    for (std::size_t i = 0; i < machines.size(); ++i) {
        CHECK(machines[i].name == embedded_machines()[i].name);
        CHECK(machines[i].text == embedded_machines()[i].text);
        CHECK(machines[i].source == "machines/" + machines[i].name + ".json");
    }
    CHECK(load_machine("fanuc").source == "machines/fanuc.json");
}

}  // namespace
}  // namespace camgen
