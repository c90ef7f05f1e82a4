#include "camgen/cli/output.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace fs = std::filesystem;

namespace {

// The temporaries a signal handler must remove. A signal handler can reach nothing else, so
// this is the one piece of process-wide state in camgen: fixed slots of plain characters,
// claimed and released with atomics (async-signal-safe to read).
constexpr int max_pending = 4;
constexpr std::size_t max_path = 4096;
char pending_paths[max_pending][max_path];
std::atomic<bool> pending_used[max_pending];

int claim_slot(const std::string& path) {
    if (path.size() + 1 > max_path) return -1;
    for (int i = 0; i < max_pending; ++i) {
        bool expected = false;
        if (!pending_used[i].load() && pending_used[i].compare_exchange_strong(expected, true)) {
            std::memcpy(pending_paths[i], path.c_str(), path.size() + 1);
            return i;
        }
    }
    return -1;
}

void release_slot(const std::string& path) {
    for (int i = 0; i < max_pending; ++i)
        if (pending_used[i].load() && path == pending_paths[i]) pending_used[i].store(false);
}

extern "C" void remove_pending_and_die(int sig) {
    for (int i = 0; i < max_pending; ++i)
        if (pending_used[i].load()) ::unlink(pending_paths[i]);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

// Holds SIGINT and SIGTERM back for its lifetime (they are delivered when it ends).
class SignalsHeld {
public:
    SignalsHeld() {
        sigset_t set;
        sigemptyset(&set);
        sigaddset(&set, SIGINT);
        sigaddset(&set, SIGTERM);
        ::pthread_sigmask(SIG_BLOCK, &set, &old_);
    }
    ~SignalsHeld() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
    SignalsHeld(const SignalsHeld&) = delete;
    SignalsHeld& operator=(const SignalsHeld&) = delete;

private:
    sigset_t old_{};
};

[[noreturn]] void fail(const std::string& path, int error) {
    throw IoError(fmt::format("cannot write {}: {}", path, std::strerror(error)));
}

// The file a path ends up at: symlinks followed (a dangling link: the file it names).
std::string resolve_target(const std::string& path) {
    fs::path p = path;
    std::error_code ec;
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        fs::path next = fs::read_symlink(p, ec);
        if (ec) fail(path, ec.value());
        p = next.is_absolute() ? next : p.parent_path() / next;
    }
    return p.string();
}

// The mode a new file gets: 0666 less the process's umask.
unsigned new_file_mode() {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return 0666u & ~static_cast<unsigned>(mask);
}

// Temporaries beside `target` are ".<name>.camgen-<pid>.XXXXXX"; those of processes that no
// longer exist were left by a killed run: remove them.
std::string temp_prefix(const fs::path& target) {
    std::string prefix = target.filename().string();
    prefix.insert(prefix.begin(), '.');
    prefix.append(".camgen-");
    return prefix;
}

void remove_stale_temporaries(const fs::path& target) {
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string prefix = temp_prefix(target);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) != 0) continue;
        const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
        if (pid <= 0 || pid == ::getpid()) continue;
        if (::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH) fs::remove(entry.path(), ec);
    }
}

}  // namespace

void install_output_signal_handlers() {
    std::signal(SIGINT, remove_pending_and_die);
    std::signal(SIGTERM, remove_pending_and_die);
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
    target_ = resolve_target(path_);
    struct stat st {};
    const bool exists = ::stat(target_.c_str(), &st) == 0;
    if (exists && S_ISDIR(st.st_mode)) fail(path_, EISDIR);
    if (exists && !S_ISREG(st.st_mode)) {
        // A FIFO, a device, a socket: write into it; replacing it would break what it is.
        out_.open(target_, std::ios::binary | std::ios::out);
        if (!out_) fail(path_, errno ? errno : EIO);
        return;
    }
    mode_ = exists ? (st.st_mode & 07777) : new_file_mode();
    const fs::path target = target_;
    remove_stale_temporaries(target);
    std::string templ = (target.has_parent_path() ? target.parent_path() / "" : fs::path()).string() +
                        temp_prefix(target) + std::to_string(::getpid()) + ".XXXXXX";
    // SIGINT and SIGTERM wait while the temporary is created and its slot claimed: a signal
    // between the two would leave a temporary the handler does not know of.
    int fd = -1;
    int create_error = 0;
    {
        const SignalsHeld held;
        fd = ::mkstemp(templ.data());
        create_error = errno;
        if (fd >= 0) claim_slot(templ);
    }
    if (fd < 0) fail(path_, create_error);
    ::close(fd);
    temp_ = templ;
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) {
        const int error = errno;
        ::unlink(temp_.c_str());
        release_slot(temp_);
        fail(path_, error);
    }
}

OutputFile::~OutputFile() {
    if (committed_ || temp_.empty()) return;
    out_.close();
    ::unlink(temp_.c_str());
    release_slot(temp_);
}

void OutputFile::commit() {
    errno = 0;
    out_.flush();
    const int flush_error = out_ ? 0 : (errno ? errno : EIO);
    out_.close();
    if (flush_error || !out_) fail(path_, flush_error ? flush_error : (errno ? errno : EIO));
    if (temp_.empty()) {
        committed_ = true;
        return;
    }
    // On disk before it takes the old file's place, with the mode the file should have.
    const int fd = ::open(temp_.c_str(), O_RDONLY);
    if (fd < 0) fail(path_, errno);
    const bool synced = ::fsync(fd) == 0 && ::fchmod(fd, static_cast<mode_t>(mode_)) == 0;
    const int sync_error = errno;
    ::close(fd);
    if (!synced) fail(path_, sync_error);
    if (std::rename(temp_.c_str(), target_.c_str()) != 0) fail(path_, errno);
    release_slot(temp_);
    committed_ = true;
}

}  // namespace camgen
