// Finding machine files (the user's folders before the built-in machines) and applying
// "extends": a machine file may give only what differs from another.
#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "camgen/common/error.hpp"
#include "camgen/common/file_kind.hpp"
#include "camgen/common/input_file.hpp"
#include "camgen/common/json_util.hpp"
#include "camgen/post/machine.hpp"
#include "camgen/post/machine_sources.hpp"
#include "src/post/machine_files.hpp"

#ifndef CAMGEN_MACHINES_FROM_BIN
#define CAMGEN_MACHINES_FROM_BIN "../share/camgen/machines"
#endif

namespace camgen {

namespace {

namespace fs = std::filesystem;

// Longer chains are a mistake (or a cycle through paths that name one file differently).
constexpr int max_extends_depth = 16;

bool is_path(const std::string& name_or_path) {
    return name_or_path.find('/') != std::string::npos || (name_or_path.size() > 5 && name_or_path.ends_with(".json"));
}

std::string stem_of(const std::string& path) {
    std::string stem = path.substr(path.find_last_of('/') + 1);
    if (stem.ends_with(".json")) stem.resize(stem.size() - 5);
    return stem;
}

// A machine file's text, within the limit of an input. The file an "extends" names
// (`named_by`: the file that extends it) must be a regular file: a FIFO would wait for a writer
// and a device may never end, so either is refused by its type before it is opened.
InputText read_file(const std::string& path, const std::string& named_by) {
    InputRules rules{.what = "machine file", .named_by = named_by.empty() ? "" : "the extends of " + named_by,
                     .regular_only = !named_by.empty(), .json = true};
    std::istringstream no_input;
    return read_input(path, rules, no_input);
}

// One file of an "extends" chain, as read.
struct Layer {
    std::string source;  // for messages: the path, or machines/NAME.json for a built-in
    std::string identity;  // the same file however it was named
    std::optional<FileId> id;  // a regular file's device and inode
    nlohmann::json doc;
    json::LineMap lines;
};

// What names a machine file however it was reached (a relative path, a link, a built-in).
std::string identity_of(const MachineEntry& e) {
    if (e.text) return "built-in " + e.name;
    std::error_code ec;
    std::string canonical = fs::weakly_canonical(e.path, ec).string();
    return ec || canonical.empty() ? e.path : canonical;
}

// Reads one file of the chain (`named_by`: the file whose extends names it, "" for the first).
Layer read_layer(const MachineEntry& e, const std::string& named_by) {
    Layer l;
    InputText input;
    if (e.text) input.text = e.text;
    else input = read_file(e.path, named_by);
    l.source = e.text ? "machines/" + e.name + ".json" : e.path;
    l.identity = identity_of(e);
    l.id = input.id;
    try {
        l.doc = json::parse(input.text, l.source);
    } catch (const InputError&) {
        // A drawing, a program, a binary file: said as such, not as a JSON syntax error.
        if (auto what = not_json(input.text, input.cut, l.source, "machine file")) throw InputError("", *what, 0, l.source);
        throw;
    }
    l.lines = json::LineMap(input.text);
    return l;
}

MachineEntry file_entry(const std::string& path) { return {stem_of(path), path, path, nullptr, false}; }

// The machine files of a folder (*.json, not hidden), sorted; none if it does not exist.
std::vector<std::string> machine_files_in(const std::string& dir) {
    std::error_code ec;
    std::vector<std::string> files;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string file = it->path().filename().string();
        if (file.size() > 5 && file.ends_with(".json") && file[0] != '.' && it->is_regular_file(ec))
            files.push_back(it->path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// "(did you mean ...); known machines: ..." for a name not in the catalogue (each name once).
std::string known_machines_hint(const std::string& name, const std::vector<MachineEntry>& catalogue) {
    std::vector<std::string> names;
    for (const auto& e : catalogue)
        if (!e.shadowed) names.push_back(e.name);
    auto hint = json::did_you_mean(name, names);
    return fmt::format("{}; known machines: {}", hint ? fmt::format(" (did you mean \"{}\"?)", *hint) : "",
                       fmt::join(names, ", "));
}

[[noreturn]] void unknown_machine(const std::string& name, const std::vector<MachineEntry>& catalogue) {
    throw UsageError(fmt::format("unknown machine \"{}\"{} (or give a path to a machine JSON file)", name,
                                 known_machines_hint(name, catalogue)));
}

// The entry a name means, searching from `from` on in the catalogue.
const MachineEntry* find_entry(const std::vector<MachineEntry>& catalogue, const std::string& name, std::size_t from = 0) {
    for (std::size_t i = from; i < catalogue.size(); ++i)
        if (catalogue[i].name == name) return &catalogue[i];
    return nullptr;
}

// The chain of files a machine is made of, the machine's own file first.
std::vector<Layer> read_chain(const std::string& name_or_path) {
    const std::vector<MachineEntry> catalogue = machine_catalogue();
    MachineEntry entry;
    if (is_path(name_or_path)) {
        entry = file_entry(name_or_path);
    } else if (const MachineEntry* e = find_entry(catalogue, name_or_path)) {
        entry = *e;
    } else {
        unknown_machine(name_or_path, catalogue);
    }
    std::vector<Layer> chain;
    std::string named_by;  // the file whose extends names the next one
    while (true) {
        chain.push_back(read_layer(entry, named_by));
        named_by = chain.back().source;
        const Layer& layer = chain.back();
        json::Source source{layer.source, layer.lines};
        if (!layer.doc.is_object()) json::fail(source, "", "a machine file is a JSON object");
        auto it = layer.doc.find("extends");
        if (it == layer.doc.end()) break;
        if (!it->is_string() || it->get<std::string>().empty())
            json::fail(source, "/extends", "expected the name or path of the machine file this one extends");
        const std::string base = it->get<std::string>();
        if (chain.size() > max_extends_depth)
            json::fail(source, "/extends", fmt::format("more than {} machine files extend each other", max_extends_depth));
        if (is_path(base)) {
            // A relative path is relative to the extending file's folder.
            fs::path p(base);
            if (p.is_relative() && !entry.path.empty()) p = fs::path(entry.path).parent_path() / p;
            entry = file_entry(p.string());
        } else {
            // A file extending its own name extends the next file of that name in the search
            // order (a user's fanuc.json extending the built-in fanuc).
            std::size_t from = 0;
            if (base == entry.name)
                for (std::size_t i = 0; i < catalogue.size(); ++i)
                    if (catalogue[i].origin == entry.origin) from = i + 1;
            const MachineEntry* e = find_entry(catalogue, base, from);
            if (!e)
                json::fail(source, "/extends",
                           fmt::format("no machine \"{}\" to extend{}", base, known_machines_hint(base, catalogue)));
            entry = *e;
        }
        // A cycle: the next file is one of the chain already.
        const std::string next = identity_of(entry);
        for (const Layer& l : chain)
            if (l.identity == next) {
                std::vector<std::string> files;
                for (const Layer& c : chain) files.push_back(c.source);
                files.push_back(l.source);
                json::fail(source, "/extends", fmt::format("a cycle of extensions: {}", fmt::join(files, " extends ")));
            }
    }
    return chain;
}

nlohmann::json merge_chain(const std::vector<Layer>& chain) {
    nlohmann::json merged = chain.back().doc;
    for (auto it = chain.rbegin() + 1; it != chain.rend(); ++it) {
        nlohmann::json patch = it->doc;
        patch.erase("extends");
        merged.merge_patch(patch);
    }
    merged.erase("extends");
    return merged;
}

// The file of the chain that gives the value at `pointer` (or its nearest parent): the
// first that has it, the machine's own file first.
InputError located_in_chain(const InputError& e, const std::vector<Layer>& chain) {
    // A refused combination of settings is named where the file nearest the machine's own
    // gives one of them: the setting its author changed.
    if (const auto* settings = dynamic_cast<const MachineSettingsError*>(&e))
        for (const Layer& l : chain)
            for (const std::string& p : settings->paths) {
                bool has = false;
                try {
                    has = l.doc.contains(nlohmann::json::json_pointer(p));
                } catch (const nlohmann::json::exception&) {
                }
                if (has) return InputError(p, e.detail(), l.lines.line_of(p), l.source);
            }
    std::string pointer = e.path();
    while (true) {
        for (const Layer& l : chain) {
            bool has = false;
            try {
                has = l.doc.contains(nlohmann::json::json_pointer(pointer));
            } catch (const nlohmann::json::exception&) {
            }
            if (!has) continue;
            int line = l.lines.line_of(pointer);
            return e.located(l.source, line);
        }
        if (pointer.empty()) return e.located(chain.front().source, 0);
        pointer.resize(pointer.rfind('/'));
    }
}

}  // namespace

std::vector<std::string> user_machine_dirs() {
    std::vector<std::string> dirs;
    if (const char* env = std::getenv("CAMGEN_MACHINES")) {
        std::string_view rest = env;
        while (!rest.empty()) {
            const std::size_t colon = rest.find(':');
            std::string_view dir = rest.substr(0, colon);
            if (!dir.empty()) dirs.emplace_back(dir);
            rest = colon == std::string_view::npos ? std::string_view{} : rest.substr(colon + 1);
        }
    }
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    // The XDG rule: an unset or relative XDG_CONFIG_HOME means ~/.config.
    if (xdg && *xdg == '/') dirs.push_back(std::string(xdg) + "/camgen/machines");
    else if (home && *home) dirs.push_back(std::string(home) + "/.config/camgen/machines");
    return dirs;
}

std::optional<std::string> installed_machine_dir() {
    // CAMGEN_MACHINES_FROM_BIN, the path from the install's bin folder to its machine files,
    // comes from the build (cmake/install.cmake). Looked up once: the executable stays put.
    static const std::optional<std::string> dir = []() -> std::optional<std::string> {
        std::error_code ec;
        const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
        if (ec) return std::nullopt;
        const fs::path machines = (exe.parent_path() / CAMGEN_MACHINES_FROM_BIN).lexically_normal();
        if (!fs::is_directory(machines, ec)) return std::nullopt;
        return machines.string();
    }();
    return dir;
}

std::vector<MachineEntry> machine_catalogue() {
    std::vector<MachineEntry> out;
    for (const std::string& dir : user_machine_dirs())
        for (const std::string& f : machine_files_in(dir)) out.push_back(file_entry(f));
    const std::size_t first_builtin = out.size();
    if (const auto installed = installed_machine_dir())
        for (const std::string& f : machine_files_in(*installed)) out.push_back({stem_of(f), "built-in, " + f, f, nullptr, false});
    else
        for (const auto& e : embedded_machines()) out.push_back({e.name, "built-in", "", e.text, false});
    std::sort(out.begin() + static_cast<std::ptrdiff_t>(first_builtin), out.end(),
              [](const MachineEntry& a, const MachineEntry& b) { return a.name < b.name; });
    for (std::size_t i = 0; i < out.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (out[j].name == out[i].name) out[i].shadowed = true;
    return out;
}

nlohmann::json resolve_machine_json(const std::string& name_or_path) { return merge_chain(read_chain(name_or_path)); }

Machine load_machine(const std::string& name_or_path) {
    std::vector<MachineSource> sources;
    return load_machine(name_or_path, sources);
}

Machine load_machine(const std::string& name_or_path, std::vector<MachineSource>& sources) {
    const std::vector<Layer> chain = read_chain(name_or_path);
    for (const Layer& l : chain)
        if (l.id) sources.push_back({l.source, *l.id});
    const std::string name = is_path(name_or_path) ? stem_of(name_or_path) : name_or_path;
    if (chain.size() == 1) return parse_machine_json(chain.front().doc, name, {chain.front().source, chain.front().lines});
    try {
        return parse_machine_json(merge_chain(chain), name, {chain.front().source, json::LineMap{}});
    } catch (const InputError& e) {
        throw located_in_chain(e, chain);
    }
}

}  // namespace camgen
