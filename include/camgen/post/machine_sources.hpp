#pragma once
// Loading a machine and naming the files it was read from (the machine's own file and those of
// its "extends" chain): the command line refuses an output that would replace one of them.
#include <string>
#include <vector>

#include "camgen/common/input_file.hpp"
#include "camgen/post/machine.hpp"

namespace camgen {

// A regular file a machine was read from.
struct MachineSource {
    std::string file;  // as named (--machine, an extends, a catalogue entry)
    FileId id;
};

// load_machine, also appending to `sources` each regular file of the chain, the machine's own
// first (a compiled-in machine has none).
Machine load_machine(const std::string& name_or_path, std::vector<MachineSource>& sources);

}  // namespace camgen
