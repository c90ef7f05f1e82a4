#pragma once
// The Sinumerik reader's factory, for the dialect registry (machines/registry.cpp).
#include <memory>
#include <string>

#include "camgen/post/machine.hpp"

namespace camgen::reader {

class NcReader;

// A reader of Sinumerik programs for `machine`; `source` names the program in messages.
std::unique_ptr<NcReader> make_sinumerik_reader(const Machine& machine, std::string source);

}  // namespace camgen::reader
