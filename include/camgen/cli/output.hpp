#pragma once
// Writing an output file atomically: into a temporary file beside it, renamed over the target
// only when everything was written. A failed run leaves no partial file, and an existing
// file survives an error.
#include <fstream>
#include <string>

namespace camgen {

class AtomicFile {
public:
    // Creates the temporary file. Throws IoError.
    explicit AtomicFile(std::string path);
    ~AtomicFile();  // removes the temporary file unless committed
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return out_; }
    // Flushes, closes and renames over the target. Throws IoError.
    void commit();

private:
    std::string path_;
    std::string temp_;
    std::ofstream out_;
    bool committed_ = false;
};

}  // namespace camgen
