#pragma once
// Helpers shared by the unit tests: run the pipeline in-process, split NC text into words.
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "camgen/error.hpp"
#include "camgen/job_json.hpp"
#include "camgen/machine.hpp"
#include "camgen/operations.hpp"
#include "camgen/post.hpp"

namespace camgen::test {

struct Posted {
    std::string text;
    std::string warnings;
};

// Posts a job given as JSON text for a machine given by name.
inline Posted post_job(const std::string& job_json, const std::string& machine_name, bool snippet = false) {
    Job job = read_job(job_json, "test.json");
    Machine machine = load_machine(machine_name);
    std::ostringstream out, warn;
    PostOptions o;
    o.snippet = snippet;
    o.program_name = job.name;
    o.warnings = &warn;
    auto post = make_post(machine, out, o);
    post->open();
    expand_job(job, *post);
    post->close();
    return {out.str(), warn.str()};
}

// The lines of a text.
inline std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// The words of one block: letter -> value text ("G02 D90 I0 J10" -> {G:02, D:90, I:0, J:10}).
inline std::map<char, std::string> words_of(const std::string& line) {
    std::map<char, std::string> w;
    std::istringstream in(line);
    for (std::string word; in >> word;)
        if (!word.empty()) w[word[0]] = word.substr(1);
    return w;
}

inline std::string read_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

}  // namespace camgen::test
