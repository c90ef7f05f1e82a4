// Error messages of bad jobs, compared with tests/errors/messages.txt: every sample (and the
// jobs in tests/errors) is broken
// in many ways (each value replaced by a wrong type, a negative, zero, a fraction, a huge
// number, null, or removed; each object given an unknown and a misspelt key; each member line
// duplicated; the text cut short), posted in-process as the command line does, and what camgen
// prints (file, line, JSON path and detail) must stay exactly the same. The file was written
// by the code before the job reader was made faster (issue 13), so a faster reader must give
// the same messages. CAMGEN_UPDATE_ERRORS=1 build/camgen_tests -tc='error messages*' rewrites it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support.hpp"

namespace camgen::test {

namespace test_error_messages {  // named: a unity build compiles several test files as one

using Ordered = nlohmann::ordered_json;

const std::filesystem::path samples_dir = std::filesystem::path(CAMGEN_SOURCE_DIR) / "samples";
const std::filesystem::path golden_path = std::filesystem::path(CAMGEN_SOURCE_DIR) / "tests/errors/messages.txt";

// The machine a sample is posted for, as scripts/update-golden draws its backplot.
std::string machine_of(const std::string& sample) {
    const auto golden = std::filesystem::path(CAMGEN_SOURCE_DIR) / "tests/golden";
    if (!std::filesystem::exists(golden / "wabeco" / (sample + ".err"))) return "wabeco";
    if (!std::filesystem::exists(golden / "fanuc" / (sample + ".err"))) return "fanuc";
    return "linuxcnc-lathe";
}

// Every JSON pointer of a document, in document order.
void pointers(const Ordered& v, const std::string& at, std::vector<std::string>& out) {
    out.push_back(at);
    if (v.is_object())
        for (const auto& [key, member] : v.items()) pointers(member, at + "/" + key, out);
    else if (v.is_array())
        for (std::size_t i = 0; i < v.size(); ++i) pointers(v[i], at + "/" + std::to_string(i), out);
}

// One bad job: what was done to which sample, and its text.
struct Case {
    std::string label;
    std::string text;
};

// The ways a value is broken.
const std::vector<std::pair<std::string, Ordered>> replacements = {
    {"string", "x"}, {"negative", -1}, {"zero", 0}, {"fraction", 2.5}, {"huge", 1e12},
    {"null", nullptr}, {"object", Ordered::object()}, {"array", Ordered::array()},
};

std::vector<Case> cases_of(const std::string& sample, const std::string& original) {
    std::vector<Case> cases;
    const Ordered doc = Ordered::parse(original);
    std::vector<std::string> all;
    pointers(doc, "", all);
    for (const std::string& p : all) {
        if (p.empty()) continue;
        const Ordered::json_pointer ptr(p);
        for (const auto& [name, value] : replacements) {
            Ordered bad = doc;
            bad[ptr] = value;
            cases.push_back({sample + " " + name + " " + p, bad.dump(2)});
        }
        Ordered bad = doc;
        Ordered& parent = bad[ptr.parent_pointer()];
        if (parent.is_object()) parent.erase(ptr.back());
        else parent.erase(static_cast<std::size_t>(std::stoul(ptr.back())));
        cases.push_back({sample + " removed " + p, bad.dump(2)});
        if (doc[ptr].is_object() && !doc[ptr].empty()) {
            Ordered unknown = doc;
            unknown[ptr]["bogusKey"] = 1;
            cases.push_back({sample + " unknown-key " + p, unknown.dump(2)});
            Ordered misspelt;
            for (const auto& [key, member] : doc[ptr].items()) misspelt[key + (misspelt.empty() ? "s" : "")] = member;
            Ordered renamed = doc;
            renamed[ptr] = misspelt;
            cases.push_back({sample + " misspelt-key " + p, renamed.dump(2)});
        }
    }
    // Text-level: a member line repeated (a duplicate key) and the text cut short.
    const std::string text = doc.dump(2);
    const auto lines = lines_of(text);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].find("\": ") == std::string::npos || lines[i].back() != ',') continue;
        std::string dup;
        for (std::size_t j = 0; j < lines.size(); ++j) dup += lines[j] + "\n" + (j == i ? lines[j] + "\n" : "");
        cases.push_back({sample + " duplicate-line " + std::to_string(i + 1), dup});
    }
    for (std::size_t cut = 0; cut < text.size(); cut += 53) cases.push_back({sample + " cut " + std::to_string(cut), text.substr(0, cut)});
    return cases;
}

// What camgen prints for a case (the job on standard input): exit code and standard error, one
// line (\n written as \\n).
// `extra`: more arguments (--tools); each (path, name) of `renamed` is written as its name.
std::string outcome(const Case& c, const std::string& machine, const std::vector<std::string>& extra = {},
                    const std::vector<std::pair<std::string, std::string>>& renamed = {}) {
    std::vector<std::string> args{"-", "--machine", machine};
    args.insert(args.end(), extra.begin(), extra.end());
    Run r = run(args, c.text);
    for (const auto& [path, name] : renamed)
        for (std::size_t at; (at = r.err.find(path)) != std::string::npos;) r.err.replace(at, path.size(), name);
    std::string flat;
    for (char ch : r.err) flat += ch == '\n' ? std::string("\\n") : std::string(1, ch);
    return std::to_string(r.code) + " " + flat;
}

}  // namespace test_error_messages

using namespace test_error_messages;

TEST_CASE("error messages of broken samples stay exactly as they were") {
    // The samples, and jobs in tests/errors made of what the samples lack: contours and paths
    // of lines only, 3D lines, inch holes.
    std::vector<std::filesystem::path> samples;
    for (const auto& dir : {samples_dir, golden_path.parent_path()})
        for (const auto& entry : std::filesystem::directory_iterator(dir))
            if (entry.path().extension() == ".json") samples.push_back(entry.path());
    std::sort(samples.begin(), samples.end());
    // CAMGEN_ERROR_STRIDE=n (the sanitized twin: 4) posts every n-th case only; each other case
    // is written as its label and "(skipped)" and compared by its label, so the list of cases is
    // still checked whole. The messages come from the same code paths; each case costs a post
    // in-process, about eleven times as long under the sanitizers.
    const char* stride_text = std::getenv("CAMGEN_ERROR_STRIDE");
    const long stride = stride_text ? std::max(1L, std::atol(stride_text)) : 1;
    const std::string skipped = " | (skipped)";
    std::ostringstream actual;
    long index = 0;
    auto add = [&](const std::string& label, const auto& posted) {
        if (index++ % stride == 0) actual << label << " | " << posted() << '\n';
        else actual << label << skipped << '\n';
    };
    for (const auto& path : samples) {
        const std::string sample = path.stem().string();
        const std::string machine = machine_of(sample);
        for (const Case& c : cases_of(sample, read_file(path.string())))
            add(c.label, [&] { return outcome(c, machine); });
    }
    // The tool library sample (samples/library): its job broken as the samples are, posted with
    // its library; and its library broken the same ways, each posted with the job.
    const std::filesystem::path library_dir = samples_dir / "library";
    const std::string library = (library_dir / "tools.json").string();
    const std::string library_job = (library_dir / "plate-library.json").string();
    const std::vector<std::pair<std::string, std::string>> library_names{{library, "samples/library/tools.json"}};
    for (const Case& c : cases_of("library-job", read_file(library_job)))
        add(c.label, [&] { return outcome(c, "fanuc", {"--tools", library}, library_names); });
    const std::filesystem::path broken = scratch("error-messages-library") / "tools.json";
    const std::string job_text = read_file(library_job);
    for (const Case& c : cases_of("library", read_file(library))) {
        add(c.label, [&] {
            std::ofstream(broken, std::ios::binary) << c.text;
            const Case posted{c.label, job_text};
            return outcome(posted, "fanuc", {"--tools", broken.string()}, {{broken.string(), "samples/library/tools.json"}});
        });
    }
    if (std::getenv("CAMGEN_UPDATE_ERRORS")) {
        REQUIRE_MESSAGE(stride == 1, "CAMGEN_UPDATE_ERRORS with CAMGEN_ERROR_STRIDE would write skipped cases");
        std::filesystem::create_directories(golden_path.parent_path());
        std::ofstream(golden_path, std::ios::binary) << actual.str();
        return;
    }
    const auto expected = lines_of(read_file(golden_path.string()));
    const auto got = lines_of(actual.str());
    REQUIRE_MESSAGE(!expected.empty(), "no " << golden_path << "; CAMGEN_UPDATE_ERRORS=1 writes it");
    int differences = 0;
    for (std::size_t i = 0; i < std::max(expected.size(), got.size()) && differences < 10; ++i) {
        std::string e = i < expected.size() ? expected[i] : "(none)";
        const std::string g = i < got.size() ? got[i] : "(none)";
        if (g.ends_with(skipped)) e = e.substr(0, e.find(" | ")) + skipped;  // the label only
        if (e != g) {
            ++differences;
            CHECK_MESSAGE(g == e, "line " << i + 1 << "\nexpected: " << e << "\n     got: " << g);
        }
    }
    CHECK(expected.size() == got.size());
}

}  // namespace camgen::test
