// Which operation each program line belongs to (operation_lines.hpp).
#include "camgen/cli/operation_lines.hpp"

#include <algorithm>
#include <functional>
#include <sstream>
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

// The posted program's lines and, for each, the index of its operation (-1: none).
struct OplinesPosted {
    std::vector<std::size_t> hashes;
    std::vector<int> op;
    std::vector<std::string> paths;
};

OplinesPosted oplines_post(const Job& job, const Machine& machine) {
    std::ostringstream text;
    PostOptions po;
    po.program_name = job.name;
    po.work_offset = job.work_offset;
    po.program_number = job.program_number;
    std::unique_ptr<Post> post = make_post(machine, text, po);
    // The line each operation starts at: the lines written before its start, plus one.
    struct Noting : EventSink {
        Post& post;
        std::ostringstream& text;
        std::vector<std::pair<std::size_t, std::string>> starts;
        std::size_t scanned = 0, lines = 0;
        Noting(Post& p, std::ostringstream& t) : post(p), text(t) {}
        void emit(const Event& e) override {
            if (const auto* o = std::get_if<OperationStart>(&e)) {
                post.flush_blocks();
                const std::string_view s = text.view();
                lines += static_cast<std::size_t>(std::count(s.begin() + static_cast<std::ptrdiff_t>(scanned), s.end(), '\n'));
                scanned = s.size();
                starts.emplace_back(lines, o->path);
            }
            post.emit(e);
        }
    } noting(*post, text);
    post->open();
    expand_job(job, noting);
    post->close();
    OplinesPosted out;
    std::istringstream in(text.str());
    std::string line;
    std::size_t k = 0;
    int current = -1;
    const std::hash<std::string_view> hash;
    while (std::getline(in, line)) {
        while (k < noting.starts.size() && noting.starts[k].first <= out.hashes.size()) {
            out.paths.push_back(noting.starts[k].second);
            current = static_cast<int>(out.paths.size()) - 1;
            ++k;
        }
        out.hashes.push_back(hash(oplines_trimmed(line)));
        out.op.push_back(current);
    }
    return out;
}

}  // namespace

OperationLines operation_lines(const Job& job, const Machine& machine, std::istream& program) {
    OperationLines result;
    OplinesPosted posted;
    try {
        posted = oplines_post(job, machine);
    } catch (const std::exception& e) {
        result.note = fmt::format("operations not known: the job does not post for {} ({})", machine.name, e.what());
        return result;
    }
    std::vector<std::size_t> lines;
    const std::hash<std::string_view> hash;
    for (std::string line; std::getline(program, line);) lines.push_back(hash(oplines_trimmed(line)));
    // Walk both; where they differ, resynchronise at the nearest pair of two equal lines within
    // a window (the fewest lines skipped on both sides together).
    constexpr std::size_t window = 64;
    const std::size_t n = lines.size(), m = posted.hashes.size();
    std::vector<int> op(n, -1);
    std::size_t i = 0, j = 0, unmatched = 0;
    int last = -1;
    auto same = [&](std::size_t a, std::size_t b) {
        return a < n && b < m && lines[a] == posted.hashes[b] && (a + 1 >= n || b + 1 >= m || lines[a + 1] == posted.hashes[b + 1]);
    };
    while (i < n && j < m) {
        if (lines[i] == posted.hashes[j]) {
            op[i] = last = posted.op[j];
            ++i, ++j;
            continue;
        }
        bool found = false;
        for (std::size_t s = 1; s <= 2 * window && !found; ++s)
            for (std::size_t a = s > window ? s - window : 0; a <= std::min(s, window) && !found; ++a)
                if (same(i + a, j + (s - a))) {
                    for (std::size_t k = 0; k < a; ++k) op[i + k] = last;  // added or changed: the operation before
                    unmatched += a;
                    i += a, j += s - a;
                    found = true;
                }
        if (!found) break;
    }
    if (i < n && j < m) {
        result.note = fmt::format("operations known up to line {} only: the program differs there from what the job posts", i);
    } else if (unmatched > 0) {
        result.note = fmt::format("{} of the program differ{} from what the job posts: counted with the operation of the line "
                                  "before",
                                  unmatched == 1 ? std::string("1 line") : fmt::format("{} lines", unmatched), unmatched == 1 ? "s" : "");
    }
    for (; i < n && j >= m; ++i) op[i] = last;  // lines beyond the posted program's end
    for (std::size_t k = 0; k < n; ++k) {
        if (op[k] < 0) continue;
        const std::string& path = posted.paths[static_cast<std::size_t>(op[k])];
        if (result.spans.empty() || result.spans.back().path != path)
            result.spans.push_back({static_cast<int>(k + 1), path});
    }
    return result;
}

}  // namespace camgen
