#pragma once
// Writing an output file (-o, --plot) so that it respects the path it is given:
// - a regular file (or a new one) is written to a temporary file beside it and renamed over
//   it only when everything was written: a failed or interrupted run leaves no partial file
//   and an existing file survives; the file keeps its mode, a new one gets 0666 less the umask;
// - a symlink is followed and its target replaced the same way (the link stays a link);
// - a FIFO, a character device (a serial line, /dev/null) or another non-regular file is
//   written into directly: it is never replaced by a regular file.
// SIGINT and SIGTERM remove the temporaries of this process (install_output_signal_handlers);
// a temporary left by a killed run (its process gone) is removed by the next run that writes
// beside it.
#include <fstream>
#include <string>

namespace camgen {

class OutputFile {
public:
    // Opens the file for writing as above. Throws IoError naming the path and the reason.
    explicit OutputFile(std::string path);
    ~OutputFile();  // removes the temporary file unless committed
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;

    std::ostream& stream() { return out_; }
    // Flushes, closes, and (for a temporary) syncs it, gives it its mode and renames it over
    // the target. Throws IoError naming the path and the reason (ENOSPC, EISDIR, ...).
    void commit();
    // The file being written to: the temporary, or the target itself.
    const std::string& written_path() const { return temp_.empty() ? target_ : temp_; }
    // Whether what is written vanishes unless committed (a temporary): then a writer may stream
    // into it, where otherwise it must hold its output until it is complete.
    bool discarded_unless_committed() const { return !temp_.empty(); }

private:
    std::string path_;    // as given, for messages
    std::string target_;  // the file that ends up written (a symlink's target)
    std::string temp_;    // empty: writing into the target directly
    unsigned mode_ = 0;   // the mode the finished file gets
    std::ofstream out_;
    bool committed_ = false;
};

// Installs SIGINT/SIGTERM handlers that remove the temporaries of every OutputFile not yet
// committed, then end the process by the signal. Call once, from main.
void install_output_signal_handlers();

}  // namespace camgen
