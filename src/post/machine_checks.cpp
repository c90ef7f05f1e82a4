// A machine file cannot break motion: its settings are checked against what its dialect writes
// and what camgen's reader reads back, so that a file that would write wrong motion (a shaft
// turned to half its diameter, G21 written as G42, G33.1 as G33, a number split at a decimal
// comma) is refused when it is read, naming the setting.
#include "camgen/post/machine_checks.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "src/post/dialect_registry.hpp"

namespace camgen {

namespace {

// The formats a machine file gives, by JSON path ("/formats/xyz", "/inchFormats/code").
std::string format_path(const std::string& key) {
    return key.starts_with("inch.") ? "/inchFormats/" + key.substr(5) : "/formats/" + key;
}

// The plane a start block word selects.
std::optional<Plane> plane_of_word(const std::string& word) {
    if (word == "G17") return Plane::xy;
    if (word == "G18") return Plane::xz;
    if (word == "G19") return Plane::yz;
    return std::nullopt;
}

std::string plane_word(Plane p) { return p == Plane::xy ? "G17" : p == Plane::xz ? "G18" : "G19"; }

std::string upper(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

// The problems of every dialect: formats. The formats of mm output first; an inch format's
// problem also names the mm format it inherits from.
std::optional<MachineProblem> format_problem(const Machine& m) {
    std::vector<std::string> keys;
    for (const auto& [key, spec] : m.formats)
        if (!key.starts_with("inch.")) keys.push_back(key);
    for (const auto& [key, spec] : m.formats)
        if (key.starts_with("inch.")) keys.push_back(key);
    for (const std::string& key : keys) {
        const nc::FormatSpec& spec = m.formats.at(key);
        const std::string family = key.starts_with("inch.") ? key.substr(5) : key;
        const std::string inch = key.starts_with("inch.") ? "inch." : "";
        auto paths = [&](const std::string& setting) {
            std::vector<std::string> p{format_path(key) + "/" + setting};
            if (!inch.empty()) p.push_back("/formats/" + family + "/" + setting);
            return p;
        };
        const std::string path = format_path(key);
        if (spec.width > 0 && !spec.zeropad) {
            std::vector<std::string> p = paths("width");
            p.push_back(path + "/zeropad");
            return MachineProblem{p, fmt::format("width {} without \"zeropad\": true pads the number with spaces "
                                                 "(X{}): no control reads a number with spaces in it; set "
                                                 "\"zeropad\": true or leave width out",
                                                 spec.width, nc::Format(spec).format(-0.5))};
        }
        const bool length = family == "xyz" || family == "ijk" || family == "x" || family == "z" || family == "i";
        if (length && std::abs(spec.scale - 1.0) > 1e-12)
            return MachineProblem{paths("scale"),
                                  fmt::format("coordinates are written in the program's units: scale {} would make "
                                              "every {} length {} times what the job says (and arcs whose centres "
                                              "are scaled otherwise run off their circles); inch output comes from "
                                              "\"units\", a lathe's diameters from xDiameterProg: leave scale out",
                                              spec.scale, family, spec.scale)};
        if (family == "x" || family == "z" || family == "i") {
            // The post checks arcs and depths, and the reader compares, at the family's resolution.
            const std::string parent = inch + (family == "i" ? "ijk" : "xyz");
            auto it = m.formats.find(parent);
            if (it == m.formats.end()) it = m.formats.find(family == "i" ? "ijk" : "xyz");
            nc::FormatSpec parent_spec;
            parent_spec.decimals = 3;
            if (it != m.formats.end()) parent_spec = it->second;
            if (spec.force_decimal != parent_spec.force_decimal) {
                std::vector<std::string> p = paths("forceDecimal");
                p.push_back(format_path(parent) + "/forceDecimal");
                return MachineProblem{p, fmt::format("{} words {} where the {} format's {}: the reader takes a "
                                                     "number without a point as the control does only where the "
                                                     "machine never writes one; give {} the same forceDecimal",
                                                     upper(family), spec.force_decimal ? "force a decimal point"
                                                                                       : "leave out trailing zeros",
                                                     family == "i" ? "ijk" : "xyz",
                                                     parent_spec.force_decimal ? "do not" : "do", family)};
            }
            if (spec.decimals != parent_spec.decimals) {
                std::vector<std::string> p = paths("decimals");
                p.push_back(format_path(parent) + "/decimals");
                return MachineProblem{
                    p, fmt::format("{} words with {} decimals where the {} format has {}: camgen rounds arcs, hole "
                                   "depths and pecks at the {} format's resolution, so {} words would land off them; "
                                   "give {} the same decimals, {}",
                                   upper(family), spec.decimals, family == "i" ? "ijk" : "xyz", parent_spec.decimals,
                                   family == "i" ? "ijk" : "xyz", upper(family), family, parent_spec.decimals)};
            }
        }
        if (family == "feedPerRev" && spec.decimals < 3)
            return MachineProblem{paths("decimals"),
                                  fmt::format("feeds per revolution are hundredths of a millimetre: {} decimals would "
                                              "write 0.05 mm/rev as {}; give feedPerRev at least 3 decimals",
                                              spec.decimals, nc::Format(spec).format(0.05))};
        if (family != "code") continue;
        if (std::abs(spec.scale - 1.0) > 1e-12)
            return MachineProblem{paths("scale"),
                                  fmt::format("G and M codes are not quantities: scale {} would write G21 as G{} and "
                                              "M3 as M{}; leave scale out of the code format",
                                              spec.scale, nc::Format(spec).format(21.0), nc::Format(spec).format(3.0))};
        if (spec.force_sign)
            return MachineProblem{paths("forceSign"),
                                  "forceSign writes G+1 and M+3: the sign is no part of a G or M code; leave "
                                  "forceSign out of the code format"};
        if (!spec.prefix.empty())
            return MachineProblem{paths("prefix"),
                                  fmt::format("a prefix of the code format is written between the letter and the "
                                              "number (G{}1): leave it out",
                                              spec.prefix)};
        if (spec.decimals < 1)
            for (size_t i = 0; i < m.drilling.size(); ++i)
                if (m.drilling[i].style == CannedStyle::rigid_g33_1) {
                    std::vector<std::string> p = paths("decimals");
                    p.push_back(fmt::format("/drilling/cycles/{}/style", i));
                    return MachineProblem{
                        p, "decimals 0 writes the rigid tap G33.1 as G33, a threading move without the spindle "
                           "reversal: the tap would be pulled out turning forward and strip the thread; give the code "
                           "format 1 decimal"};
                }
    }
    return std::nullopt;
}

}  // namespace

std::optional<MachineProblem> single_arc_plane_problem(const Machine& m, Plane control_default) {
    if (m.arcs.planes.size() != 1) return std::nullopt;
    const Plane arcs = m.arcs.planes.front();
    Plane start = control_default;
    std::string where = fmt::format("the control starts in {} ({})", plane_word(start), upper(name_of(plane_names, start)));
    std::vector<std::string> paths{"/arcs/planes"};
    for (size_t i = 0; i < m.frame.start_block.size(); ++i)
        if (auto p = plane_of_word(m.frame.start_block[i])) {
            start = *p;
            where = fmt::format("the start block selects {} ({})", m.frame.start_block[i], upper(name_of(plane_names, start)));
            paths = {fmt::format("/frame/startBlock/{}", i), "/arcs/planes"};
        }
    if (start == arcs) return std::nullopt;
    if (paths.size() == 1) paths.push_back("/frame/startBlock");
    const std::string name = upper(name_of(plane_names, arcs));
    return MachineProblem{
        paths, fmt::format("arcs.planes is [\"{}\"] alone, so no plane word is written on arc blocks, but {}: every {} "
                           "arc would be read in the wrong plane; select {} in the start block, or list \"{}\" in "
                           "arcs.planes too (each arc block then selects its plane)",
                           name_of(plane_names, arcs), where, name, plane_word(arcs), name_of(plane_names, start))};
}

std::optional<MachineProblem> diameter_mode_problem(const Machine& m, std::string_view word, bool diameter,
                                                    std::string_view word_means) {
    const auto& b = m.frame.start_block;
    const auto it = std::find(b.begin(), b.end(), word);
    if (it == b.end() || m.x_diameter == diameter) return std::nullopt;
    const std::string path = fmt::format("/frame/startBlock/{}", it - b.begin());
    if (diameter)
        return MachineProblem{
            {"/globals/xDiameterProg", path},
            fmt::format("the start block's {} ({}) makes the control read X as a diameter, but xDiameterProg is "
                        "false, so camgen writes X as a radius: every X would be cut at half its radius (a 30 mm "
                        "shaft turned to 15 mm); set xDiameterProg to true, or take {} out of the start block",
                        word, word_means, word)};
    return MachineProblem{
        {"/globals/xDiameterProg", path},
        fmt::format("the start block's {} ({}) makes the control read X as a radius, but xDiameterProg is true, so "
                    "camgen writes X as a diameter: every X would be cut at twice its radius; set xDiameterProg to "
                    "false, or take {} out of the start block",
                    word, word_means, word)};
}

std::optional<MachineProblem> xy_arcs_only_problem(const Machine& m, std::string_view form) {
    for (size_t i = 0; i < m.arcs.planes.size(); ++i)
        if (m.arcs.planes[i] != Plane::xy)
            return MachineProblem{
                {fmt::format("/arcs/planes/{}", i), "/arcs/planes"},
                fmt::format("the {} dialect writes arcs in the XY plane only ({}): an {} arc would be cut as an XY "
                            "arc; set \"planes\": [\"xy\"] (arcs in other planes are then written as lines)",
                            m.dialect, form, upper(name_of(plane_names, m.arcs.planes[i])))};
    return std::nullopt;
}

std::optional<MachineProblem> decimal_point_only_problem(const Machine& m, std::string_view why) {
    if (m.decimal_mark == '.') return std::nullopt;
    return MachineProblem{{"/globals/decimalMark"},
                          fmt::format("the {} dialect's controls read a decimal point only: {}; set decimalMark "
                                      "to \".\"",
                                      m.dialect, why)};
}

std::optional<MachineProblem> start_block_problem(const Machine& m, std::span<const std::string_view> unit_words,
                                                  std::span<const std::string_view> known_words) {
    const auto& b = m.frame.start_block;
    std::optional<size_t> plane;
    for (size_t i = 0; i < b.size(); ++i) {
        const std::string path = fmt::format("/frame/startBlock/{}", i);
        if (std::find(unit_words.begin(), unit_words.end(), b[i]) != unit_words.end())
            return MachineProblem{{path}, fmt::format("{} is a unit word: camgen writes the unit word from \"units\" "
                                                      "(and --units) after the start block; take {} out",
                                                      b[i], b[i])};
        if (plane_of_word(b[i])) {
            if (plane)
                return MachineProblem{{path, fmt::format("/frame/startBlock/{}", *plane)},
                                      fmt::format("{} and {}: two planes in one block, which the control refuses; "
                                                  "keep one",
                                                  b[*plane], b[i])};
            plane = i;
        }
        if (std::find(known_words.begin(), known_words.end(), b[i]) == known_words.end())
            return MachineProblem{
                {path}, fmt::format("{} is not a word of a {} safe start that camgen writes and reads back (motion, "
                                    "compensation, incremental, feed-per-revolution and other modes would change every "
                                    "move after it); the start block may hold {}",
                                    b[i], m.dialect, fmt::join(known_words, " "))};
    }
    return std::nullopt;
}

std::optional<MachineProblem> machine_problem(const Machine& machine) {
    if (auto p = format_problem(machine)) return p;
    if (const Dialect* d = find_dialect(machine.dialect); d && d->check_machine) return d->check_machine(machine);
    return std::nullopt;
}

}  // namespace camgen
