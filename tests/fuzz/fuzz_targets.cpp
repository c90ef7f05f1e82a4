#include "fuzz_targets.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "camgen/analysis/compare.hpp"
#include "camgen/analysis/trace.hpp"
#include "camgen/common/error.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/post/post.hpp"
#include "camgen/reader/reader.hpp"
#include "camgen/operations/registry.hpp"

namespace camgen::fuzz {

namespace {

// Inputs beyond this are cut: the targets look for wrong behaviour, not for slow big jobs.
constexpr std::size_t max_input = 64 * 1024;
// A small job budget keeps each input fast.
constexpr JobLimits limits{2000, 2000, 64};
// Programs are posted up to this size and then dropped, neither finished nor read back: a job of
// a few hundred bytes can ask for millions of lines (a bore's helix at 0.0006 mm a turn is 20,000
// turns, 151 MB of chords on kosy, 4.7 s in Release), and posting or reading those under the
// sanitizers outlasts any timeout. Big programs are measured by bench/run and ctest
// readback/memory.
constexpr std::size_t max_program = 4 * 1024 * 1024;

// The program's text, refused beyond max_program: the stream then fails, and the post's next
// flush (every 1 MB) stops it with an IoError.
class BoundedText : public std::streambuf {
public:
    std::string text;
    bool too_big = false;

protected:
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        if (text.size() + static_cast<std::size_t>(n) > max_program) {
            too_big = true;
            return 0;
        }
        text.append(s, static_cast<std::size_t>(n));
        return n;
    }
    int_type overflow(int_type c) override {
        if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
        const char ch = traits_type::to_char_type(c);
        return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
    }
};

const std::vector<Machine>& machines() {
    static const std::vector<Machine> all = [] {
        std::vector<Machine> m;
        for (const auto& [name, description] : list_machines()) m.push_back(load_machine(name));
        return m;
    }();
    return all;
}

// Posts a job for a machine; nullopt when the machine refuses it (an InputError) or the program
// grows beyond max_program.
std::optional<std::string> post(const Job& job, const Machine& machine) {
    BoundedText text;
    std::ostream out(&text);
    PostOptions o;
    o.program_name = job.name;
    auto p = make_post(machine, out, o);
    try {
        check_machine_kind(job, machine.kind, machine.name);
        p->open();
        expand_job(job, *p);
        p->close();
    } catch (const InputError&) {
        return std::nullopt;
    } catch (const IoError&) {
        if (text.too_big) return std::nullopt;
        throw;
    }
    if (text.too_big) return std::nullopt;
    return std::move(text.text);
}

// Runs `f`, turning an unexpected exception into a finding.
template <class F>
std::optional<std::string> guarded(F&& f) {
    try {
        return f();
    } catch (const InputError&) {
        return std::nullopt;
    } catch (const UsageError&) {
        return std::nullopt;
    } catch (const std::exception& e) {
        return std::string("unexpected exception: ") + e.what();
    }
}

std::vector<std::string> sample_texts() {
    std::vector<std::filesystem::path> paths;
    for (const auto& e : std::filesystem::directory_iterator(CAMGEN_SOURCE_DIR "/samples"))
        if (e.path().extension() == ".json") paths.push_back(e.path());
    std::sort(paths.begin(), paths.end());
    std::vector<std::string> texts;
    for (const auto& p : paths) {
        std::ifstream in(p, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        texts.push_back(s.str());
    }
    return texts;
}

// Every number of a JSON document, in document order.
void numbers_of(nlohmann::json& j, std::vector<nlohmann::json*>& out) {
    if (j.is_number()) out.push_back(&j);
    if (j.is_array() || j.is_object())
        for (auto& v : j) numbers_of(v, out);
}

}  // namespace

std::optional<std::string> job_input(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), std::min(size, max_input));
    return guarded([&]() -> std::optional<std::string> {
        // Whatever the fast JSON reader reads, nlohmann's must read to the same document.
        if (const auto fast = json::parse_document_fast(text, limits.nesting)) {
            try {
                if (json::fingerprint(*fast) != json::fingerprint(json::parse_document_with_nlohmann(text, "fuzz.json", limits.nesting)))
                    return std::string("the fast JSON reader and nlohmann's read different documents");
            } catch (const InputError& e) {
                return std::string("the fast JSON reader took a text nlohmann's refuses: ") + e.what();
            }
        }
        const Job job = read_job(text, "fuzz.json", limits);
        for (const Machine& m : machines()) (void)post(job, m);
        return std::nullopt;
    });
}

std::optional<std::string> program_input(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), std::min(size, max_input));
    for (const Machine& m : machines()) {
        auto problem = guarded([&]() -> std::optional<std::string> {
            const auto events = read_program(text, m, "fuzz.nc");
            (void)trace_program(events, m);
            return std::nullopt;
        });
        if (problem) return m.name + ": " + *problem;
    }
    return std::nullopt;
}

std::optional<std::string> mutated_sample(const std::uint8_t* data, std::size_t size) {
    static const std::vector<std::string> samples = sample_texts();
    if (size < 2 || samples.empty()) return std::nullopt;
    size = std::min(size, max_input);
    nlohmann::json job = nlohmann::json::parse(samples[data[0] % samples.size()]);
    const Machine& machine = machines()[data[1] % machines().size()];
    std::vector<nlohmann::json*> numbers;
    numbers_of(job, numbers);
    // Each 3 bytes: which number, and how it changes (scaled, shifted, or set).
    for (std::size_t i = 2; i + 2 < size && !numbers.empty(); i += 3) {
        nlohmann::json& n = *numbers[data[i] % numbers.size()];
        const double v = n.get<double>();
        const int k = static_cast<int8_t>(data[i + 2]);
        switch (data[i + 1] % 4) {
            case 0: n = v * (1.0 + k / 128.0); break;
            case 1: n = v + k / 16.0; break;
            case 2: n = static_cast<double>(k); break;
            default: n = std::round(v * 1000.0 + k) / 1000.0; break;
        }
    }
    const std::string text = job.dump();
    return guarded([&]() -> std::optional<std::string> {
        const Job parsed = read_job(text, "mutant.json", limits);
        const std::optional<std::string> program = post(parsed, machine);
        if (!program) return std::nullopt;
        ReadResolution resolution;
        Trace actual;
        try {
            actual = trace_program(read_program(*program, machine, "mutant", &resolution), machine);
        } catch (const InputError& e) {
            return "machine " + machine.name + " cannot read back its own program: " + e.what() + "\njob: " + text;
        }
        const Trace expected = trace_expected(expand_job(parsed), machine, parsed.work_offset);
        if (auto m = compare_traces(expected, actual, compare_tolerance(machine, resolution)))
            return "machine " + machine.name + ", line " + std::to_string(m->line) + ": " + m->message + "\njob: " + text;
        return std::nullopt;
    });
}

}  // namespace camgen::fuzz
