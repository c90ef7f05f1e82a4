// Which operation each program line belongs to (operation_lines.hpp).
#include "camgen/cli/operation_lines.hpp"

#include <algorithm>
#include <deque>
#include <streambuf>
#include <functional>
#include <string_view>

#include <fmt/format.h>

#include "camgen/operations/registry.hpp"
#include "camgen/post/post.hpp"

namespace camgen {

namespace {

// A line as compared: without trailing blanks and carriage return.
std::string_view oplines_trimmed(std::string_view s) {
    while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

// The posted program as it is written: each finished line's hash handed on, so that neither
// the posted text nor its lines are kept (a program of a million lines is matched in a window).
class OplinesSplitter : public std::streambuf {
public:
    explicit OplinesSplitter(std::function<void(std::size_t)> on_line) : on_line_(std::move(on_line)) { setp(buf_, buf_ + sizeof buf_); }
    // Hands on the text written so far (sync) and the last line if it has no newline (finish).
    void finish() {
        drain();
        if (!partial_.empty()) done(partial_);
        partial_.clear();
    }

protected:
    int_type overflow(int_type c) override {
        drain();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    int sync() override {
        drain();
        return 0;
    }

private:
    void done(std::string_view line) { on_line_(std::hash<std::string_view>{}(oplines_trimmed(line))); }
    void drain() {
        std::string_view text(pbase(), static_cast<std::size_t>(pptr() - pbase()));
        for (std::size_t nl; (nl = text.find('\n')) != std::string_view::npos; text.remove_prefix(nl + 1)) {
            if (partial_.empty()) {
                done(text.substr(0, nl));
            } else {
                partial_.append(text.substr(0, nl));
                done(partial_);
                partial_.clear();
            }
        }
        partial_.append(text);
        setp(buf_, buf_ + sizeof buf_);
    }
    std::function<void(std::size_t)> on_line_;
    std::string partial_;
    char buf_[1 << 16];
};

// The program's lines against the posted ones, as the posted ones arrive: where they differ,
// resynchronised at the nearest pair of two equal lines within a window (the fewest lines skipped
// on both sides together). Keeps only the lines of the window.
class OplinesMatcher {
public:
    explicit OplinesMatcher(std::istream& program) : program_(program) {}

    // A posted line: its hash and its operation (-1: none).
    void posted(std::size_t hash, int op) {
        if (diverged_ || program_ended()) return;  // no line of the program is left to match
        posted_.push_back({hash, op});
        advance(false);
    }

    // After the last posted line: the operation of each line, and the note.
    OperationLines finish(const std::vector<std::string>& paths) {
        advance(true);
        OperationLines result;
        if (diverged_) {
            result.note = fmt::format("operations known up to line {} only: the program differs there from what the job posts", i_);
        } else {
            if (unmatched_ > 0)
                result.note = fmt::format("{} of the program differ{} from what the job posts: counted with the operation of "
                                          "the line before",
                                          unmatched_ == 1 ? std::string("1 line") : fmt::format("{} lines", unmatched_),
                                          unmatched_ == 1 ? "s" : "");
            if (have_program(i_)) assign(i_, last_);  // lines beyond the posted program's end
        }
        for (const auto& [line, op] : spans_) {
            const std::string& path = paths[static_cast<std::size_t>(op)];
            if (result.spans.empty() || result.spans.back().path != path) result.spans.push_back({line, path});
        }
        return result;
    }

private:
    static constexpr std::size_t window = 64;

    bool have_program(std::size_t k) {
        while (p0_ + program_hashes_.size() <= k && !program_end_) {
            if (std::getline(program_, line_)) program_hashes_.push_back(std::hash<std::string_view>{}(oplines_trimmed(line_)));
            else program_end_ = true;
        }
        return k < p0_ + program_hashes_.size();
    }
    bool program_ended() { return !have_program(i_); }
    bool have_posted(std::size_t k) const { return k < q0_ + posted_.size(); }
    std::size_t program_at(std::size_t k) const { return program_hashes_[k - p0_]; }
    const std::pair<std::size_t, int>& posted_at(std::size_t k) const { return posted_[k - q0_]; }
    // Line k (0-based) belongs to operation op.
    void assign(std::size_t k, int op) {
        if (op >= 0 && (spans_.empty() || spans_.back().second != op)) spans_.emplace_back(static_cast<int>(k + 1), op);
    }
    void advance(bool final) {
        while (!diverged_ && have_program(i_) && have_posted(j_)) {
            if (program_at(i_) == posted_at(j_).first) {
                assign(i_, last_ = posted_at(j_).second);
                ++i_, ++j_;
                drop();
                continue;
            }
            if (!final && !have_posted(j_ + 2 * window + 1)) return;  // the window's posted lines are not written yet
            auto same = [&](std::size_t a, std::size_t b) {
                return have_program(a) && have_posted(b) && program_at(a) == posted_at(b).first &&
                       (!have_program(a + 1) || !have_posted(b + 1) || program_at(a + 1) == posted_at(b + 1).first);
            };
            bool found = false;
            for (std::size_t s = 1; s <= 2 * window && !found; ++s)
                for (std::size_t a = s > window ? s - window : 0; a <= std::min(s, window) && !found; ++a)
                    if (same(i_ + a, j_ + (s - a))) {
                        for (std::size_t k = 0; k < a; ++k) assign(i_ + k, last_);  // added or changed: the operation before
                        unmatched_ += a;
                        i_ += a, j_ += s - a;
                        found = true;
                    }
            if (!found) diverged_ = true;
            drop();
        }
    }
    void drop() {
        while (p0_ < i_ && !program_hashes_.empty()) program_hashes_.pop_front(), ++p0_;
        while (q0_ < j_ && !posted_.empty()) posted_.pop_front(), ++q0_;
    }

    std::istream& program_;
    std::string line_;
    std::deque<std::size_t> program_hashes_;  // lines p0_..
    std::size_t p0_ = 0;
    bool program_end_ = false;
    std::deque<std::pair<std::size_t, int>> posted_;  // lines q0_..: hash and operation
    std::size_t q0_ = 0;
    std::size_t i_ = 0, j_ = 0, unmatched_ = 0;  // the next program and posted lines
    int last_ = -1;
    bool diverged_ = false;
    std::vector<std::pair<int, int>> spans_;  // first line (1-based), operation
};

}  // namespace

OperationLines operation_lines(const Job& job, const Machine& machine, std::istream& program) {
    OplinesMatcher matcher(program);
    std::vector<std::string> paths;
    int current = -1;
    OplinesSplitter splitter([&](std::size_t hash) { matcher.posted(hash, current); });
    try {
        std::ostream text(&splitter);
        PostOptions po;
        po.program_name = job.name;
        po.work_offset = job.work_offset;
        po.program_number = job.program_number;
        std::unique_ptr<Post> post = make_post(machine, text, po);
        // Each operation's lines: those finished after its start (the blocks before it flushed).
        struct Noting : EventSink {
            Post& post;
            std::vector<std::string>& paths;
            int& current;
            Noting(Post& p, std::vector<std::string>& ps, int& c) : post(p), paths(ps), current(c) {}
            void emit(const Event& e) override {
                if (const auto* o = std::get_if<OperationStart>(&e)) {
                    post.flush_blocks();
                    paths.push_back(o->path);
                    current = static_cast<int>(paths.size()) - 1;
                }
                post.emit(e);
            }
        } noting(*post, paths, current);
        post->open();
        expand_job(job, noting);
        post->close();
        text.flush();
        splitter.finish();
    } catch (const std::exception& e) {
        OperationLines result;
        result.note = fmt::format("operations not known: the job does not post for {} ({})", machine.name, e.what());
        return result;
    }
    return matcher.finish(paths);
}

}  // namespace camgen
