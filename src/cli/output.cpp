#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/cli/output.hpp"

namespace camgen {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    std::string templ = path_ + ".tmp-XXXXXX";
    int fd = mkstemp(templ.data());
    if (fd < 0) throw IoError(fmt::format("cannot write {}: {}", path_, std::strerror(errno)));
    ::close(fd);
    temp_ = templ;
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) {
        std::remove(temp_.c_str());
        throw IoError(fmt::format("cannot write {}: {}", path_, std::strerror(errno)));
    }
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        out_.close();
        std::remove(temp_.c_str());
    }
}

void AtomicFile::commit() {
    out_.flush();
    out_.close();
    if (!out_) throw IoError(fmt::format("cannot write {}: writing failed", path_));
    if (std::rename(temp_.c_str(), path_.c_str()) != 0)
        throw IoError(fmt::format("cannot write {}: {}", path_, std::strerror(errno)));
    committed_ = true;
}

}  // namespace camgen
