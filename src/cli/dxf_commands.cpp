#include "camgen/cli/dxf_commands.hpp"

#include <algorithm>
#include <optional>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "camgen/common/number_text.hpp"
#include "camgen/geometry/vec.hpp"

namespace camgen {

namespace {

using OJson = nlohmann::ordered_json;

// A number for the job: a whole number as an integer (15, not 15.0), else 4 decimals at most.
OJson dxf_cmd_json_number(double v) {
    const double r = std::round(v * 1e4) / 1e4;
    if (r == std::round(r) && std::abs(r) < 1e12) return OJson(static_cast<long long>(r));
    return OJson(r);
}

// A length of the drawing as text: 4 decimals at most, no trailing zeros.
std::string dxf_cmd_number(double v) { return number_text(v, 4); }

std::string dxf_cmd_units(const dxf::Drawing& d) {
    std::string name;
    const std::optional<double> mm = dxf::mm_per_unit(d.insunits, &name);
    if (!mm) return d.insunits == 0 ? "no units given ($INSUNITS 0)" : fmt::format("units camgen does not take ($INSUNITS {})", d.insunits);
    return fmt::format("{} ($INSUNITS {})", name, d.insunits);
}

std::string dxf_cmd_extent(const Profile& p) {
    const dxf::Box b = dxf::extent(p);
    return fmt::format("X {} .. {}  Y {} .. {}", dxf_cmd_number(b.min.x), dxf_cmd_number(b.max.x), dxf_cmd_number(b.min.y),
                       dxf_cmd_number(b.max.y));
}

std::string dxf_cmd_chain_words(const dxf::Chain& c) {
    std::string s = dxf::describe(c.pieces.front()->origin);
    if (c.pieces.size() > 1) s += fmt::format(" and {} more", c.pieces.size() - 1);
    return s;
}

// What dxf-info reports, tallied piece by piece as the reader hands them on: only the path
// pieces are kept (to be chained); circles and points are counted.
struct DxfCmdTally {
    std::size_t pieces = 0, points = 0;
    // Per layer name (as the pieces spell it), the count of each entity type.
    std::map<std::string_view, std::map<std::string_view, std::size_t>> by_layer;
    // Circles by diameter (to 0.0001 drawing units): how many, on which layers.
    std::map<long long, std::pair<std::size_t, std::set<std::string_view>>> by_diameter;
    std::vector<dxf::Piece> paths;

    void add(dxf::Piece&& p) {
        ++pieces;
        ++by_layer[p.origin.layer][p.origin.type];
        if (p.kind == dxf::Piece::Kind::circle) {
            auto& d = by_diameter[std::llround(p.radius * 2 * 1e4)];
            ++d.first;
            d.second.insert(p.origin.layer);
        } else if (p.kind == dxf::Piece::Kind::point) {
            ++points;
        } else {
            paths.push_back(std::move(p));
        }
    }

    std::string text(const dxf::Drawing& d) {
        std::string out = fmt::format("{}: {}, {} entit{} in model space (inserts expanded)\n", d.name, dxf_cmd_units(d), pieces,
                                      pieces == 1 ? "y" : "ies");
        out += "layers:\n";
        for (const dxf::Layer& l : d.layers) {
            std::size_t count = 0;
            std::string list;
            if (const auto found = by_layer.find(l.name); found != by_layer.end())
                for (const auto& [type, n] : found->second) {
                    list += fmt::format("{}{} {}", list.empty() ? "" : ", ", type, n);
                    count += n;
                }
            out += fmt::format("  {:<16} {:>8}{}{}\n", l.name, count, list.empty() ? "" : "  ", list);
        }
        // The path pieces of each layer chained (gap 0.01 drawing units), layer by layer, their
        // paths moved into the chains.
        std::vector<dxf::Chain> chains;
        std::vector<std::string_view> chain_layer;
        std::vector<std::string> notes;
        for (const dxf::Layer& l : d.layers) {
            std::vector<dxf::Piece*> pieces_of;
            for (dxf::Piece& p : paths)
                if (p.origin.layer == l.name) pieces_of.push_back(&p);
            if (pieces_of.empty()) continue;
            dxf::ChainResult r = dxf::chain_taking(pieces_of, 0.01, d.name);
            for (dxf::Chain& c : r.chains) {
                chains.push_back(std::move(c));
                chain_layer.push_back(l.name);
            }
            notes.insert(notes.end(), r.notes.begin(), r.notes.end());
        }
        for (bool closed : {true, false}) {
            std::size_t n = 0;
            for (const dxf::Chain& c : chains) n += c.closed == closed ? 1 : 0;
            out += fmt::format("{} profiles: {}\n", closed ? "closed" : "open", n);
            for (std::size_t i = 0; i < chains.size(); ++i) {
                const dxf::Chain& c = chains[i];
                if (c.closed != closed) continue;
                out += fmt::format("  layer {}: {} segment{}, {}{}; from {}\n", chain_layer[i], c.profile.segments.size(),
                                   c.profile.segments.size() == 1 ? "" : "s", dxf_cmd_extent(c.profile),
                                   closed ? fmt::format(", area {}", dxf_cmd_number(std::abs(enclosed_area(c.profile)))) : "",
                                   dxf_cmd_chain_words(c));
            }
        }
        // Circles by diameter, smallest first.
        out += fmt::format("circles by diameter: {}\n", by_diameter.size());
        for (const auto& [key, entry] : by_diameter) {
            const auto& [count, layers] = entry;
            std::string names;
            for (std::string_view l : layers) (names += names.empty() ? "" : ", ").append(l);
            out += fmt::format("  diameter {}: {} circle{} on layer{} {}\n", dxf_cmd_number(double(key) / 1e4), count, count == 1 ? "" : "s",
                               layers.size() == 1 ? "" : "s", names);
        }
        out += fmt::format("points: {}\n", points);
        for (const std::string& n : d.notes) out += "note: " + n + "\n";
        for (const std::string& n : notes) out += "note: " + n + "\n";
        return out;
    }
};

}  // namespace

std::string dxf_info_text(const dxf::Drawing& d) {
    DxfCmdTally tally;
    for (const dxf::Piece& p : d.pieces) tally.add(dxf::Piece(p));
    return tally.text(d);
}

std::string dxf_info_file(const std::string& path) {
    DxfCmdTally tally;
    const dxf::Drawing d = dxf::read_file(path, [&](dxf::Piece&& p) { tally.add(std::move(p)); });
    return tally.text(d);
}

namespace {

// The starter job's pieces of geometry and how each operation names them.
struct DxfCmdStarter {
    const dxf::Drawing& d;
    double factor = 1.0;  // job units per drawing unit
    std::string dxf_path;

    OJson point(Vec2 p) const { return OJson::array({dxf_cmd_json_number(p.x * factor), dxf_cmd_json_number(p.y * factor)}); }

    // The non-point pieces the selection takes (none when it fails).
    std::set<const dxf::Piece*> selected(const dxf::Selection& s, bool with_points) const {
        std::set<const dxf::Piece*> out;
        try {
            for (const dxf::Piece* p : dxf::select(d, s, "geometry"))
                if (with_points || p->kind != dxf::Piece::Kind::point) out.insert(p);
        } catch (const dxf::Error&) {
        }
        return out;
    }

    // The one layer of all `pieces`, or "".
    static std::string common_layer(const std::set<const dxf::Piece*>& pieces) {
        std::string layer;
        for (const dxf::Piece* p : pieces) {
            if (!layer.empty() && p->origin.layer != layer) return "";
            layer = std::string(p->origin.layer);
        }
        return layer;
    }

    // A profile as the job's start and path.
    void inline_profile(OJson& o, const Profile& p) const {
        o["start"] = point(p.start);
        OJson path = OJson::array();
        for (const ProfileSegment& s : p.segments) {
            if (s.centre)
                path.push_back({{"arc", {{"end", point(s.end)}, {"centre", point(*s.centre)}, {"direction", s.direction == ArcDirection::cw ? "cw" : "ccw"}}}});
            else
                path.push_back({{"line", point(s.end)}});
        }
        o["path"] = path;
    }
};

}  // namespace

std::string starter_job_text(const dxf::Drawing& d, const std::string& dxf_path, double end_mill_mm, std::vector<std::string>& notes) {
    const std::optional<double> mm = dxf::mm_per_unit(d.insunits);
    const bool inch = d.insunits == 1;
    DxfCmdStarter st{d, 1.0, dxf_path};
    if (mm) st.factor = inch ? 1.0 : *mm;
    else notes.push_back(fmt::format("{} gives no units ($INSUNITS): the job takes it in mm", d.name));
    const double unit_mm = inch ? 25.4 : 1.0;  // mm per job unit
    auto length = [&](double v_mm) { return dxf_cmd_json_number(v_mm / unit_mm); };

    // Every closed chain of the drawing (circles too), nested.
    std::vector<const dxf::Piece*> all;
    for (const dxf::Piece& p : d.pieces)
        if (p.kind != dxf::Piece::Kind::point) all.push_back(&p);
    const dxf::ChainResult chained = dxf::chain(all, 0.01 / (mm ? *mm : 1.0), d.name);
    for (const std::string& n : chained.notes) notes.push_back(n);
    const std::vector<dxf::Chain>& chains = chained.chains;
    const std::vector<int> parent = dxf::nesting(chains);
    auto is_circle = [&](std::size_t i) { return chains[i].pieces.size() == 1 && chains[i].pieces[0]->kind == dxf::Piece::Kind::circle; };
    int outline = -1;
    double outline_area = 0;
    for (std::size_t i = 0; i < chains.size(); ++i) {
        if (!chains[i].closed) {
            notes.push_back(fmt::format("the open profile from {} is left out: a starter job cuts closed profiles", dxf_cmd_chain_words(chains[i])));
            continue;
        }
        if (parent[i] >= 0 || is_circle(i)) continue;
        const double a = std::abs(enclosed_area(chains[i].profile));
        if (a > outline_area) {
            outline_area = a;
            outline = static_cast<int>(i);
        }
    }
    std::vector<std::size_t> pockets;
    std::map<std::size_t, std::vector<std::size_t>> islands;
    std::map<long long, std::vector<std::size_t>> holes;  // by diameter, 0.0001 drawing units
    for (std::size_t i = 0; i < chains.size(); ++i) {
        if (!chains[i].closed || static_cast<int>(i) == outline) continue;
        const int up = parent[i];
        if (is_circle(i) && (up < 0 || up == outline)) {
            holes[std::llround(chains[i].pieces[0]->radius * 2 * 1e4)].push_back(i);
        } else if (outline >= 0 && up == outline) {
            pockets.push_back(i);
        } else if (up >= 0 && parent[static_cast<std::size_t>(up)] == outline && outline >= 0 && !is_circle(static_cast<std::size_t>(up))) {
            islands[static_cast<std::size_t>(up)].push_back(i);
        } else if (up < 0) {
            notes.push_back(fmt::format("the closed profile from {} lies outside the outline: left out", dxf_cmd_chain_words(chains[i])));
        } else {
            notes.push_back(fmt::format("the closed profile from {} lies inside an island: left out", dxf_cmd_chain_words(chains[i])));
        }
    }

    OJson job;
    std::string stem = dxf_path.substr(dxf_path.find_last_of('/') + 1);
    if (const std::size_t dot = stem.find_last_of('.'); dot != std::string::npos && dot > 0) stem.resize(dot);
    job["name"] = stem;
    job["units"] = inch ? "inch" : "mm";
    job["clearance"] = length(15);
    OJson tools = OJson::array(), ops = OJson::array();
    int number = 0;
    // A drill per diameter, smallest first; rpm for about 60 m/min, feed 0.05 mm per turn.
    for (const auto& [key, list] : holes) {
        // A circle under 0.01 job units across (a point marker, a drawing in microns) is no
        // hole a drill makes, and its diameter range (0.001 either side) would go below 0.
        if (double(key) / 1e4 * st.factor < 0.01) {
            notes.push_back(fmt::format("{} circle{} of diameter {} {} left out: too small to drill", list.size(),
                                        list.size() == 1 ? "" : "s", number_text(double(key) / 1e4 * st.factor, 6),
                                        inch ? "inch" : "mm"));
            continue;
        }
        const double dia_mm = double(key) / 1e4 * (mm ? *mm : 1.0);
        const int rpm = static_cast<int>(std::clamp(std::round(60000.0 / (pi * dia_mm) / 100) * 100, 300.0, 6000.0));
        ++number;
        tools.push_back({{"number", number}, {"type", "drill"}, {"diameter", length(dia_mm)}, {"tipAngle", 118}, {"rpm", rpm},
                         {"comment", fmt::format("{} mm drill", number_text(dia_mm, 3))}});
        OJson op{{"type", "drill"}, {"tool", number}, {"cycle", "drill"},
                 {"comment", fmt::format("{} hole{} of diameter {} (edit endDepth: the drawing gives no depth)", list.size(),
                                         list.size() == 1 ? "" : "s", number_text(double(key) / 1e4 * st.factor, 4))},
                 {"retractPlane", length(5)}, {"safeDistance", length(1)}, {"endDepth", length(6)}, {"plungingFeedrate", length(std::round(rpm * 0.05))}};
        std::set<const dxf::Piece*> want;
        for (std::size_t i : list) want.insert(chains[i].pieces[0]);
        // The diameter range in job units, 0.001 either side.
        const double dia_job = std::round(double(key) / 1e4 * st.factor * 1e4) / 1e4;
        const double lo = std::round((dia_job - 0.001) * 1e4) / 1e4, hi = std::round((dia_job + 0.001) * 1e4) / 1e4;
        dxf::Selection by_diameter;
        by_diameter.min_diameter = lo / st.factor;
        by_diameter.max_diameter = hi / st.factor;
        dxf::Selection by_layer = by_diameter;
        const std::string layer = DxfCmdStarter::common_layer(want);
        if (!layer.empty()) by_layer.layers = {layer};
        if (st.selected(by_diameter, true) == want) {
            op["drawing"] = {{"dxf", dxf_path}, {"diameter", {dxf_cmd_json_number(lo), dxf_cmd_json_number(hi)}}};
        } else if (!layer.empty() && st.selected(by_layer, true) == want) {
            op["drawing"] = {{"dxf", dxf_path}, {"layer", layer}, {"diameter", {dxf_cmd_json_number(lo), dxf_cmd_json_number(hi)}}};
        } else {
            OJson pts = OJson::array();
            for (std::size_t i : list) pts.push_back(st.point(chains[i].pieces[0]->centre));
            op["holes"] = pts;
        }
        ops.push_back(op);
    }
    const int mill = ++number;
    if (outline >= 0) {
        tools.push_back({{"number", mill}, {"type", "end-mill"}, {"diameter", length(end_mill_mm)}, {"rpm", 8000},
                         {"comment", fmt::format("{} mm end mill", number_text(end_mill_mm, 3))}});
    }
    // The pockets, then the outline (the part stays held until its outline is cut).
    for (std::size_t k : pockets) {
        OJson op{{"type", "pocket"}, {"tool", mill},
                 {"comment", fmt::format("pocket from {} (edit endDepth)", dxf_cmd_chain_words(chains[k]))},
                 {"retractPlane", length(5)}, {"safeDistance", length(1)}, {"endDepth", length(3)}, {"stepDown", length(1.5)},
                 {"feed", length(500)}};
        std::set<const dxf::Piece*> want(chains[k].pieces.begin(), chains[k].pieces.end());
        for (std::size_t i : islands[k]) want.insert(chains[i].pieces.begin(), chains[i].pieces.end());
        const std::string layer = DxfCmdStarter::common_layer(want);
        dxf::Selection s;
        s.layers = {layer};
        if (!layer.empty() && st.selected(s, false) == want) {
            op["profile"] = {{"dxf", dxf_path}, {"layer", layer}};
        } else {
            st.inline_profile(op, chains[k].profile);
            if (!islands[k].empty()) {
                OJson list = OJson::array();
                for (std::size_t i : islands[k]) {
                    OJson island;
                    st.inline_profile(island, chains[i].profile);
                    list.push_back(island);
                }
                op["islands"] = list;
            }
        }
        ops.push_back(op);
    }
    if (outline >= 0) {
        const dxf::Chain& c = chains[static_cast<std::size_t>(outline)];
        OJson op{{"type", "contour"}, {"tool", mill},
                 {"comment", fmt::format("the outline from {}, outside (edit endDepth: the stock's thickness and a little)", dxf_cmd_chain_words(c))},
                 {"retractPlane", length(5)}, {"safeDistance", length(1)}, {"endDepth", length(6)}, {"stepDown", length(3)},
                 {"side", "outside"}, {"feed", length(500)}};
        const std::set<const dxf::Piece*> want(c.pieces.begin(), c.pieces.end());
        const std::string layer = DxfCmdStarter::common_layer(want);
        dxf::Selection s;
        s.layers = {layer};
        if (!layer.empty() && st.selected(s, false) == want) op["profile"] = {{"dxf", dxf_path}, {"layer", layer}};
        else st.inline_profile(op, c.profile);
        ops.push_back(op);
    } else {
        notes.push_back("the drawing has no closed profile (other than circles): no contour and no pockets");
    }
    job["tools"] = tools;
    job["operations"] = ops;
    return job.dump(2) + "\n";
}

}  // namespace camgen
