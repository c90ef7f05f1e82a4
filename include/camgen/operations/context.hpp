#pragma once
// What an operation's expansion may know besides the operation itself.
#include "camgen/job/job.hpp"

namespace camgen {

struct Context {
    const JobHeader& job;
    const Tool& tool;
};

}  // namespace camgen
