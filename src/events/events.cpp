#include "camgen/events/events.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "camgen/events/visit.hpp"


namespace camgen {

namespace {

nlohmann::ordered_json xyz(const Vec3& v) { return {v.x, v.y, v.z}; }


void put_optional(nlohmann::ordered_json& j, const char* key, const std::optional<double>& v) {
    if (v) j[key] = *v;
}

}  // namespace

std::string event_to_json(const Event& event) {
    nlohmann::ordered_json j;
    visit_exhaustive(overloaded{
                   [&](const OperationStart& e) {
                       j = {{"event", "operation-start"}, {"name", e.name}, {"path", e.path}};
                       put_optional(j, "tolerance", e.tolerance);
                       if (!e.notes.empty()) j["notes"] = e.notes;
                       if (e.feed_mode != FeedMode::per_minute) j["feedMode"] = name_of(feed_modes, e.feed_mode);
                   },
                   [&](const OperationEnd&) { j = {{"event", "operation-end"}}; },
                   [&](const ToolChange& e) {
                       j = {{"event", "tool-change"}, {"tool", e.number}, {"diameter", e.diameter}, {"description", e.description}};
                   },
                   [&](const Spindle& e) {
                       j = {{"event", "spindle"},
                            {"state", e.state == SpindleState::cw ? "cw" : e.state == SpindleState::ccw ? "ccw" : "off"},
                            {"rpm", e.rpm}};
                       if (e.surface_speed > 0) j["surfaceSpeed"] = e.surface_speed;
                   },
                   [&](const Coolant& e) { j = {{"event", "coolant"}, {"mode", name_of(coolant_modes, e.mode)}}; },
                   [&](const Rapid& e) { j = {{"event", "rapid"}, {"to", xyz(e.to)}}; },
                   [&](const Linear& e) {
                       j = {{"event", "linear"}, {"to", xyz(e.to)}, {"feed", e.feed}};
                       if (e.movement != Movement::cutting) j["movement"] = name_of(movements, e.movement);
                   },
                   [&](const Arc& e) {
                       j = {{"event", "arc"},         {"to", xyz(e.to)},
                            {"centre", xyz(e.centre)}, {"direction", e.direction == ArcDirection::cw ? "cw" : "ccw"},
                            {"plane", name_of(plane_names, e.plane)}, {"feed", e.feed}};
                       if (e.turns) j["turns"] = e.turns;
                       if (e.movement != Movement::cutting) j["movement"] = name_of(movements, e.movement);
                   },
                   [&](const Dwell& e) { j = {{"event", "dwell"}, {"seconds", e.seconds}}; },
                   [&](const Compensation& e) {
                       j = {{"event", "compensation"},
                            {"side", e.side == CompensationSide::off ? "off" : e.side == CompensationSide::left ? "left" : "right"}};
                       if (e.d_register) j["d"] = e.d_register;
                       if (e.radius > 0) j["radius"] = e.radius;
                       if (e.orientation != 0) j["orientation"] = e.orientation;
                   },
                   [&](const DrillCycle& e) {
                       j = {{"event", "drill-cycle"},  {"cycle", name_of(cycle_kinds, e.kind)}, {"path", e.path},
                            {"retractZ", e.retract_z}, {"referenceZ", e.reference_z},     {"safeZ", e.safe_z},
                            {"bottomZ", e.bottom_z},   {"feed", e.feed},                  {"rpm", e.spindle_rpm}};
                       if (e.spindle_direction == SpindleDirection::ccw) j["direction"] = "ccw";
                       if (e.unsupported != UnsupportedCycle::refuse) j["unsupported"] = name_of(unsupported_cycles, e.unsupported);
                       for (const auto& d : drill_fields) {
                           const std::optional<double> v = e.values.get(d.field);
                           if (!v) continue;
                           if (d.field == DrillField::degression_type)
                               j[d.key] = name_of(degression_types, e.values.degression_type());
                           else
                               j[d.key] = *v;
                       }
                   },
                   [&](const DrillPoint& e) { j = {{"event", "drill-point"}, {"at", {e.at.x, e.at.y}}}; },
                   [&](const DrillEnd&) { j = {{"event", "drill-end"}}; },
                   [&](const Comment& e) { j = {{"event", "comment"}, {"text", e.text}}; },
                   [&](const Stop& e) {
                       j = {{"event", "stop"}, {"optional", e.kind == StopKind::optional}, {"message", e.message}};
                       if (e.spin_up > 0) j["spinUp"] = e.spin_up;
                   },
                   [&](const ThreadFeed& e) { j = {{"event", "thread-feed"}, {"to", xyz(e.to)}, {"lead", e.lead}}; },
                   [&](const ThreadCycle& e) {
                       j = {{"event", "thread-cycle"},   {"path", e.path},
                            {"output", name_of(cycle_outputs, e.output)},
                            {"start", xyz(e.start)},     {"endZ", e.end_z},
                            {"lead", e.lead},            {"crestX", e.crest_x},
                            {"firstDepth", e.first_depth}, {"depth", e.depth},
                            {"degression", e.degression}, {"minDepth", e.min_depth},
                            {"infeedAngle", e.infeed_angle}, {"springPasses", e.spring_passes},
                            {"fields", e.fields},        {"depths", e.depths}};
                       if (e.runout > 0) j["runout"] = e.runout;
                   },
                   [&](const TurnCycle& e) {
                       j = {{"event", "turn-cycle"}, {"path", e.path}, {"output", name_of(cycle_outputs, e.output)},
                            {"start", xyz(e.start)}, {"depth", e.depth}, {"retract", e.retract}, {"feed", e.feed}};
                       nlohmann::ordered_json profile = nlohmann::ordered_json::array();
                       profile.push_back({e.profile.start.x, e.profile.start.y});
                       for (const ProfileSegment& s : e.profile.segments) {
                           nlohmann::ordered_json seg = {{"to", {s.end.x, s.end.y}}};
                           if (s.centre)
                               seg["centre"] = {s.centre->x, s.centre->y},
                               seg["direction"] = s.direction == ArcDirection::cw ? "cw" : "ccw";
                           profile.push_back(seg);
                       }
                       j["profile"] = profile;
                       j["moves"] = e.moves.size();
                       if (e.refusal) j["refusal"] = *e.refusal;
                       if (e.along_x) j["alongX"] = true;
                       if (e.lift > 0) j["exit"] = {{"lift", e.lift}, {"x", e.out_x}, {"z", e.out_z}};
                       if (e.finish)
                           j["finish"] = {{"path", e.finish->path},
                                          {"allowance", {e.finish->allowance.x, e.finish->allowance.y}},
                                          {"feed", e.finish->feed}};
                   },
                   [&](const FinishCycle& e) {
                       j = {{"event", "finish-cycle"}, {"path", e.path}, {"output", name_of(cycle_outputs, e.output)},
                            {"rough", e.rough_path}, {"start", {e.start.x, e.start.y}}, {"feed", e.feed},
                            {"moves", e.plain.size()}};
                       if (e.along_x) j["alongX"] = true;
                       if (e.refusal) j["refusal"] = *e.refusal;
                   },
                   [&](const GrooveCycle& e) {
                       j = {{"event", "groove-cycle"}, {"path", e.path},
                            {"output", name_of(cycle_outputs, e.output)},
                            {"start", xyz(e.start())}, {"width", e.width},
                            {"rightPoint", e.right_point}, {"air", e.air},
                            {"surface", e.surface}, {"bottom", e.bottom},
                            {"finish", e.finish}, {"firstZ", e.first_z},
                            {"lastZ", e.last_z}, {"zStep", e.z_step},
                            {"chamfer", e.chamfer}, {"peck", e.peck},
                            {"retract", e.retract}, {"fullRetract", e.full_retract},
                            {"dwell", e.dwell}, {"feed", e.feed},
                            {"fields", e.fields}};
                       if (e.side != GrooveSide::external)
                           j["side"] = e.side == GrooveSide::internal ? "internal" : "face";
                   },
                   [&](const CustomBlock& e) {
                       j = {{"event", "custom"}, {"path", e.path}};
                       nlohmann::ordered_json texts = nlohmann::ordered_json::object();
                       for (const CustomText& t : e.texts) texts[t.name] = t.lines;
                       j["text"] = texts;
                   },
               },
               event);
    return j.dump();
}

std::vector<Event> thread_cycle_moves(const ThreadCycle& c, ThreadCyclePattern pattern) {
    std::vector<Event> out;
    // Out of the material: +X outside an external thread, -X inside an internal one.
    const double out_dir = c.start.x >= c.crest_x ? 1.0 : -1.0;
    const double t = std::tan(c.infeed_angle * 3.14159265358979323846 / 180.0);
    const bool fanuc = pattern == ThreadCyclePattern::fanuc_g76;
    out.reserve(5 * c.depths.size());
    for (double d : c.depths) {
        // (a chamfered runout ends the pass depth - d outside the crest: the return lies as far
        // beyond it as the drive line lies beyond the crest, as LinuxCNC's G76 returns)
        const double back = fanuc && !(c.runout > 0) ? c.start.x : c.start.x + out_dir * (c.depth - d);
        const double z0 = c.start.z - d * t;
        const double z1 = c.end_z + (c.depth - d) * t;
        const double r = c.crest_x - out_dir * d;
        // (Fanuc: along Z at the start X to the pass's start, none under a radial infeed)
        if (!fanuc || t != 0.0) out.emplace_back(Rapid{{back, c.start.y, z0}});
        out.emplace_back(Rapid{{r, c.start.y, z0}});
        if (c.runout > 0) {
            out.emplace_back(ThreadFeed{{r, c.start.y, z1 + c.runout}, c.lead});
            out.emplace_back(ThreadFeed{{r + out_dir * c.depth, c.start.y, z1}, c.lead});
        } else {
            out.emplace_back(ThreadFeed{{r, c.start.y, z1}, c.lead});
        }
        out.emplace_back(Rapid{{back, c.start.y, z1}});
        if (fanuc) out.emplace_back(Rapid{c.start});
    }
    return out;
}

Vec2 fanuc_g71_start(const TurnCycle& c) {
    return c.along_x ? Vec2{c.start.z + c.depth, c.start.x} : Vec2{c.start.z, c.start.x + c.depth};
}

std::vector<LatheCycleMove> turn_cycle_path(const TurnCycle& c, RoughCyclePattern pattern) {
    if (pattern == RoughCyclePattern::fanuc_g71 && !c.refusal && !c.moves.empty()) {
        const LatheCycleAxis axis = c.along_x ? LatheCycleAxis::x : LatheCycleAxis::z;
        const Vec2 a = fanuc_g71_start(c);
        // Linked to a G70 (read_job): the finishing shape moved by the allowances; else the boundary.
        LatheCycleModel m = c.finish ? fanuc_g7x(axis, a, fanuc_g7x_shape(axis, a, c.finish->shape), c.depth, c.retract,
                                                 c.finish->allowance)
                                     : fanuc_g7x(axis, a, fanuc_g7x_shape(axis, a, c.profile), c.depth, c.retract);
        if (!m.refusal) return std::move(m.moves);
    }
    return c.moves;
}

namespace {
// The way out from where the control's moves `path` end.
std::vector<Event> turn_cycle_exit_from(const TurnCycle& c, RoughCyclePattern pattern, const std::vector<LatheCycleMove>& path) {
    std::vector<Event> out;
    if (!(c.lift > 0) || path.empty()) return out;
    const Vec2 end = path.back().end;
    const double y = c.start.y;
    // Fanuc's control ends at A, in air beyond the part (where it was before the cycle): out
    // from there at rapid. LinuxCNC's ends on the last pass: a feed off it first.
    const bool at_a = pattern == RoughCyclePattern::fanuc_g71 && distance(end, fanuc_g71_start(c)) < 1e-9;
    Vec2 at = end;
    if (!at_a) {
        at = Vec2{end.x + c.lift, end.y + c.lift};
        out.emplace_back(Linear{Vec3{at.y, y, at.x}, c.feed, Movement::lead_out});
    }
    const double r = std::max(c.out_x, at.y);
    if (!at_a || r != at.y) out.emplace_back(Rapid{Vec3{r, y, at.x}});
    out.emplace_back(Rapid{Vec3{r, y, c.out_z}});
    return out;
}
}  // namespace

std::vector<Event> turn_cycle_exit(const TurnCycle& c, RoughCyclePattern pattern) {
    return turn_cycle_exit_from(c, pattern, turn_cycle_path(c, pattern));
}

Vec3 turn_cycle_end(const TurnCycle& c, RoughCyclePattern pattern) {
    const std::vector<LatheCycleMove> path = turn_cycle_path(c, pattern);
    if (path.empty()) return c.start;
    const std::vector<Event> exit = turn_cycle_exit_from(c, pattern, path);
    if (!exit.empty()) {
        if (const auto* r = std::get_if<Rapid>(&exit.back())) return r->to;
    }
    return Vec3{path.back().end.y, c.start.y, path.back().end.x};
}

std::vector<Event> turn_cycle_moves(const TurnCycle& c, RoughCyclePattern pattern) {
    std::vector<Event> out;
    const std::vector<LatheCycleMove> path = turn_cycle_path(c, pattern);
    out.reserve(path.size() + 3);
    const double y = c.start.y;
    Vec3 at = c.start;
    for (const LatheCycleMove& m : path) {
        const Vec3 to{m.end.y, y, m.end.x};
        if (to == at) continue;  // the cycle's first move, to where it starts
        at = to;
        switch (m.kind) {
            case LatheCycleMove::Kind::rapid: out.emplace_back(Rapid{to}); break;
            case LatheCycleMove::Kind::feed: out.emplace_back(Linear{to, c.feed, Movement::cutting}); break;
            case LatheCycleMove::Kind::arc:
                out.emplace_back(Arc{to, Vec3{m.centre.y, y, m.centre.x}, m.direction, Plane::xz, c.feed, 0, Movement::cutting});
                break;
        }
    }
    for (Event& e : turn_cycle_exit_from(c, pattern, path)) out.push_back(std::move(e));
    return out;
}

Profile finish_cycle_written_shape(const FinishCycle& c) {
    const LatheCycleAxis axis = c.along_x ? LatheCycleAxis::x : LatheCycleAxis::z;
    return fanuc_g7x_shape(axis, c.start, c.shape);
}

std::vector<Event> finish_cycle_moves(const FinishCycle& c, RoughCyclePattern pattern) {
    std::vector<Event> out;
    if (!finish_cycle_g70(c, pattern)) {
        for (const PlainMove& m : c.plain) std::visit([&](const auto& e) { out.emplace_back(e); }, m);
        return out;
    }
    const LatheCycleAxis axis = c.along_x ? LatheCycleAxis::x : LatheCycleAxis::z;
    const LatheCycleModel g70 = fanuc_g70(axis, c.start, finish_cycle_written_shape(c));
    if (g70.refusal) throw std::logic_error("finish cycle: " + *g70.refusal);
    out = finish_cycle_entry(c);
    Vec3 at{c.start.y, 0.0, c.start.x};
    bool first_feed = true;
    for (const LatheCycleMove& m : g70.moves) {
        const Vec3 to{m.end.y, 0.0, m.end.x};
        if (to == at) continue;
        at = to;
        // The feed from A' to the shape's start is the lead-in, the rest the finishing pass.
        const Movement movement = first_feed ? Movement::lead_in : Movement::finishing;
        switch (m.kind) {
            case LatheCycleMove::Kind::rapid: out.emplace_back(Rapid{to}); break;
            case LatheCycleMove::Kind::feed:
                out.emplace_back(Linear{to, c.feed, movement});
                first_feed = false;
                break;
            case LatheCycleMove::Kind::arc:
                out.emplace_back(Arc{to, Vec3{m.centre.y, 0.0, m.centre.x}, m.direction, Plane::xz, c.feed, 0, movement});
                first_feed = false;
                break;
        }
    }
    for (Event& e : finish_cycle_exit(c)) out.push_back(std::move(e));
    return out;
}

std::vector<Event> finish_cycle_entry(const FinishCycle& c) {
    // From the clearance along Z at A's radius to A (the roughing tool's way in and out).
    const Vec3 a{c.start.y, 0.0, c.start.x};
    return {Rapid{Vec3{a.x, 0.0, c.clearance}}, Rapid{a}};
}

std::vector<Event> finish_cycle_exit(const FinishCycle& c) {
    // Out of the bar at rapid from A (in air beyond the part), then to the clearance.
    const Vec3 a{c.start.y, 0.0, c.start.x};
    const double r = std::max(c.out_x, a.x);
    std::vector<Event> out;
    if (r != a.x) out.emplace_back(Rapid{Vec3{r, 0.0, a.z}});
    out.emplace_back(Rapid{Vec3{r, 0.0, c.clearance}});
    return out;
}

Vec3 finish_cycle_end(const FinishCycle& c, RoughCyclePattern pattern) {
    if (finish_cycle_g70(c, pattern)) return std::get<Rapid>(finish_cycle_exit(c).back()).to;
    for (auto it = c.plain.rbegin(); it != c.plain.rend(); ++it) {
        if (const auto* r = std::get_if<Rapid>(&*it)) return r->to;
        if (const auto* l = std::get_if<Linear>(&*it)) return l->to;
        if (const auto* a = std::get_if<Arc>(&*it)) return a->to;
    }
    throw std::logic_error("finish cycle without moves");
}

bool GrooveCycle::plain() const {
    for (const std::string& f : fields)
        if (f != "pecks") return false;
    return true;
}

std::vector<double> GrooveCycle::plunges() const {
    std::vector<double> out{first_z};
    if (z_step > 0)
        for (int k = 1; first_z - k * z_step > last_z + 1e-9 && out.size() < 100000; ++k) out.push_back(first_z - k * z_step);
    if (first_z > last_z + 1e-9) out.push_back(last_z);
    return out;
}

std::vector<Event> groove_cycle_moves(const GrooveCycle& c) {
    std::vector<Event> out;
    const std::vector<double> zs = c.plunges();
    const bool plain = c.plain();
    // Depths in the groove's own coordinate d = into * (radius or Z): falling into the material
    // on every side; P maps one back.
    const double s = c.into();
    const double air = s * c.air, surface = s * c.surface, bottom = s * c.bottom;
    auto P = [&](double d, double z) { return c.at(s * d, z); };
    const double end = bottom + c.finish;  // where the plunges stop
    // One plunge from the air level at left-corner Z z: pecks counted from `from_r` down to `to_r`.
    auto plunge = [&](double z, double from_r, double to_r) {
        std::vector<double> depths;
        if (c.peck > 0)
            for (int k = 1; from_r - k * c.peck > to_r + 1e-9; ++k) {
                // (read_groove_pecks allows at most groove_max_pecks; this stops a GrooveCycle made otherwise.)
                if (depths.size() >= 100000) throw std::logic_error("groove cycle: more than 100000 pecks in one plunge");
                depths.push_back(from_r - k * c.peck);
            }
        depths.push_back(to_r);
        for (std::size_t k = 0; k < depths.size(); ++k) {
            if (k > 0) {
                const double back = std::min(depths[k - 1] + c.retract, air);
                if (c.full_retract) out.emplace_back(Rapid{P(air, z)});
                out.emplace_back(Rapid{P(back, z)});
            }
            out.emplace_back(Linear{P(depths[k], z), c.feed, Movement::plunge});
        }
    };
    if (plain) {
        for (std::size_t k = 0; k < zs.size(); ++k) {
            if (k > 0) out.emplace_back(Rapid{P(air, zs[k])});
            plunge(zs[k], air, end);
            out.emplace_back(Rapid{P(air, zs[k])});
        }
        if (zs.size() > 1) out.emplace_back(Rapid{c.start()});
        return out;
    }
    const bool one = zs.size() == 1;
    for (std::size_t k = 0; k < zs.size(); ++k) {
        if (k > 0) out.emplace_back(Rapid{P(air, zs[k])});
        plunge(zs[k], surface, end);
        if (one && c.dwell > 0) out.emplace_back(Dwell{c.dwell});
        if (k + 1 < zs.size()) out.emplace_back(Rapid{P(air, zs[k])});
    }
    const double right_wall = c.first_z;  // the left corner at the +Z wall
    if (!one) {
        // The last plunge stands at the -Z wall: on to the bottom and along it to the +Z wall.
        if (c.finish > 0) out.emplace_back(Linear{P(bottom, c.last_z), c.feed, Movement::plunge});
        if (c.dwell > 0) out.emplace_back(Dwell{c.dwell});
        out.emplace_back(Linear{P(bottom, right_wall), c.feed, Movement::cutting});
        if (c.dwell > 0) out.emplace_back(Dwell{c.dwell});
        out.emplace_back(Rapid{P(air, right_wall)});
    } else {
        out.emplace_back(Rapid{P(air, zs.back())});
    }
    if (c.chamfer > 0) {
        const double ch = c.chamfer, a = air - surface;
        const double z_right = right_wall + c.width;  // the +Z wall
        // The +Z edge: the right corner from the chamfer's line extended to the air level down to
        // its foot on the wall.
        out.emplace_back(Rapid{P(air, z_right + ch + a - c.width)});
        out.emplace_back(Linear{P(surface - ch, right_wall), c.feed, Movement::cutting});
        out.emplace_back(Rapid{P(air, right_wall)});
        // The -Z edge: the left corner likewise.
        out.emplace_back(Rapid{P(air, c.last_z - ch - a)});
        out.emplace_back(Linear{P(surface - ch, c.last_z), c.feed, Movement::cutting});
        out.emplace_back(Rapid{P(air, c.last_z)});
    }
    return out;
}

Vec3 thread_cycle_end(const ThreadCycle& c, ThreadCyclePattern pattern) {
    if (pattern == ThreadCyclePattern::fanuc_g76) return c.start;
    return {c.start.x, c.start.y, c.end_z};
}

Vec3 groove_cycle_end(const GrooveCycle& c) {
    const std::vector<Event> moves = groove_cycle_moves(c);
    for (auto it = moves.rbegin(); it != moves.rend(); ++it) {
        if (const auto* r = std::get_if<Rapid>(&*it)) return r->to;
        if (const auto* l = std::get_if<Linear>(&*it)) return l->to;
    }
    return c.start();
}

void EventPrinter::emit(const Event& event) { out_ << event_to_json(event) << '\n'; }

}  // namespace camgen
