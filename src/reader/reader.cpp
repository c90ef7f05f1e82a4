// Reading programs through the dialect registry (machines/registry.cpp), which names each
// dialect's reader beside its post.
#include <functional>
#include <istream>
#include <mutex>
#include <deque>
#include <map>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/reader/reader.hpp"
#include "src/post/dialect_registry.hpp"
#include "src/reader/nc_reader.hpp"

namespace camgen {

namespace reader {

std::unique_ptr<NcReader> make_reader(const Machine& machine, std::string source) {
    if (const Dialect* d = find_dialect(machine.dialect); d && d->make_reader) return d->make_reader(machine, std::move(source));
    std::vector<std::string> names;
    for (const Dialect& d : dialects())
        if (d.make_reader) names.emplace_back(d.name);
    throw InputError("/dialect",
                     fmt::format("camgen cannot read programs of dialect \"{}\" (machine {}) yet; it reads: {}",
                                 machine.dialect, machine.name, fmt::join(names, ", ")),
                     0, machine.source);
}

}  // namespace reader

namespace {
// The table behind OffsetWord: the words in the order met (a deque: an entry never moves, so a
// reference to one stays good), and each word's place. Looked up and added under a lock (readers
// may run in several threads).
struct OffsetWords {
    std::mutex lock;
    std::deque<std::string> words{std::string()};
    std::map<std::string, std::uint32_t, std::less<>> index;
};
OffsetWords& offset_words() {
    static OffsetWords table;
    return table;
}
}  // namespace

OffsetWord::OffsetWord(std::string_view text) {
    if (text.empty()) return;
    OffsetWords& t = offset_words();
    const std::lock_guard guard(t.lock);
    auto it = t.index.find(text);
    if (it == t.index.end()) {
        it = t.index.emplace(std::string(text), static_cast<std::uint32_t>(t.words.size())).first;
        t.words.emplace_back(text);
    }
    id_ = it->second;
}

const std::string& OffsetWord::str() const {
    OffsetWords& t = offset_words();
    const std::lock_guard guard(t.lock);
    return t.words[id_];
}

void read_program(std::string_view text, const Machine& machine, const std::string& source, ReadEventSink& sink,
                  ReadResolution* resolution) {
    auto reader = reader::make_reader(machine, source);
    reader->read(text, sink);
    sink.finish();
    if (resolution) *resolution = reader->coarsest_resolution();
}

std::vector<ReadEvent> read_program(std::string_view text, const Machine& machine, const std::string& source,
                                    ReadResolution* resolution) {
    struct Collect : ReadEventSink {
        std::vector<ReadEvent> events;
        void read_event(const ReadEvent& e) override { events.push_back(e); }
    } collect;
    read_program(text, machine, source, collect, resolution);
    return std::move(collect.events);
}

ProgramReader::ProgramReader(std::istream& in, const Machine& machine, const std::string& source, ReadEventSink& sink)
    : in_(in), sink_(sink), reader_(reader::make_reader(machine, source)), bounds_(source.empty() ? "the program" : source) {
    reader_->start(sink);
}

ProgramReader::~ProgramReader() = default;

bool ProgramReader::advance() {
    if (done_) return false;
    // Blocks of 64 KiB: a line longer than what is left of one moves to the front and the
    // block grows until the line ends, up to the limit of a line (max_program_line); the bytes
    // are counted against the limit of an input.
    constexpr std::size_t block = std::size_t{1} << 16;
    std::size_t nl = buffer_.find('\n', next_);
    while (nl == std::string::npos && in_) {
        buffer_.erase(0, next_);
        next_ = 0;
        bounds_.line(buffer_.size(), line_ + 1);
        const std::size_t kept = buffer_.size();
        buffer_.resize(kept + block);
        in_.read(buffer_.data() + kept, static_cast<std::streamsize>(block));
        const std::size_t got = static_cast<std::size_t>(in_.gcount());
        buffer_.resize(kept + got);
        bounds_.add(got);
        nl = buffer_.find('\n', kept);
    }
    bounds_.line((nl == std::string::npos ? buffer_.size() : nl) - next_, line_ + 1);
    ++line_;
    if (nl == std::string::npos) {
        if (in_.bad()) throw IoError("cannot read the program");
        if (next_ < buffer_.size()) {  // a last line without its line break
            reader_->read_line(std::string_view(buffer_).substr(next_));
            next_ = buffer_.size();
            return true;
        }
        done_ = true;
        reader_->finish();
        sink_.finish();
        return false;
    }
    reader_->read_line(std::string_view(buffer_).substr(next_, nl - next_));
    next_ = nl + 1;
    return true;
}

void ProgramReader::read_all() {
    while (advance()) {
    }
}

ReadResolution ProgramReader::coarsest_resolution() const { return reader_->coarsest_resolution(); }

ReadResolution read_resolution(const Machine& machine) { return reader::make_reader(machine, {})->resolution(); }

LinesReadBack read_lines_back(const Machine& machine, std::string_view program, int first, int count) {
    auto reader = reader::make_reader(machine, "custom block");
    LinesReadBack out;
    int number = 0;  // the line being read
    struct Sink : ReadEventSink {
        std::function<void(const ReadEvent&)> f;
        void read_event(const ReadEvent& e) override { f(e); }
    } sink;
    sink.f = [&](const ReadEvent& e) {
        if (number >= first) out.events.emplace_back(number - first, e.event);
    };
    reader->start(sink);
    const int last = first + count - 1;
    for (std::size_t at = 0; at < program.size() && number < last;) {
        std::size_t nl = program.find('\n', at);
        if (nl == std::string_view::npos) nl = program.size();
        const std::string_view line = program.substr(at, nl - at);
        at = nl + 1;
        ++number;
        if (number == first) out.state_before = reader->modal_state();
        std::string_view trimmed = line;
        while (!trimmed.empty() && (trimmed.front() == ' ' || trimmed.front() == '\t')) trimmed.remove_prefix(1);
        while (!trimmed.empty() && (trimmed.back() == ' ' || trimmed.back() == '\t' || trimmed.back() == '\r'))
            trimmed.remove_suffix(1);
        if (number >= first && !trimmed.empty() && reader->is_frame_line(trimmed)) out.frame_lines.push_back(number - first);
        try {
            reader->read_line(line);
        } catch (const InputError& e) {
            if (number < first)
                throw std::logic_error("the program around a custom block cannot be read back: " + std::string(e.what()));
            out.error = std::make_pair(number - first, e.detail());
            return out;
        }
    }
    if (number < last) throw std::logic_error("the program with a custom block ends before it");
    out.state_after = reader->modal_state();
    return out;
}

bool has_reader(const std::string& dialect) {
    const Dialect* d = find_dialect(dialect);
    return d && d->make_reader;
}

}  // namespace camgen
