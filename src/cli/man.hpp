#pragma once
// The man page camgen.1, written from the same CLI11 option table as --help (the build runs
// `camgen --man` to make it), so the two cannot drift apart.
#include <string>

#include <CLI/CLI.hpp>

namespace camgen {

// The roff text of camgen(1) for this command line: name, synopsis, description, every
// option and subcommand with the names, arguments and descriptions --help shows, then the
// files camgen reads and the exit status.
std::string man_page(const CLI::App& app, const std::string& version);

}  // namespace camgen
