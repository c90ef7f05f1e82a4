#include "camgen/operations/part_guard.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "camgen/events/visit.hpp"

namespace camgen {

namespace {

// The tag a tool move carries back from the compensation: its movement, and whether a rapid.
std::size_t tag(Movement m, bool rapid) { return static_cast<std::size_t>(m) * 2 + (rapid ? 1 : 0); }
Movement movement_of(std::size_t tag) { return static_cast<Movement>(tag / 2); }
bool rapid_of(std::size_t tag) { return tag % 2 == 1; }

std::string show(double v) {
    std::string s = fmt::format("{:.3f}", v);
    if (s == "-0.000") s = "0.000";
    return s;
}

}  // namespace

std::string movement_words(Movement m, bool rapid) {
    if (rapid) return "rapid";
    switch (m) {
        case Movement::cutting: return "pass";
        case Movement::plunge: return "plunge";
        case Movement::ramp: return "ramp";
        case Movement::lead_in: return "lead-in";
        case Movement::lead_out: return "lead-out";
        case Movement::finishing: return "finishing pass";
    }
    return "move";
}

PartGuard::PartGuard(const GuardedPart& part)
    : part_(part),
      clearance_(*part.profile, part.tool_radius + 1.0),
      comp_([this](const CompMove& m) { check(m); }),
      reach_(part.tool_radius + 1.0) {
    for (const Profile* island : part_.islands) island_clearances_.emplace_back(*island, reach_);
}

void PartGuard::keep(double wall_stock, double floor_z) {
    comp_.flush();
    wall_ = wall_stock;
    floor_ = floor_z;
    // The clearance answers exactly up to its reach: the stock must fit in it.
    if (wall_ >= reach_ - part_.tool_radius - 0.5) {
        reach_ = part_.tool_radius + wall_ + 1.0;
        clearance_ = ProfileClearance(*part_.profile, reach_);
        island_clearances_.clear();
        for (const Profile* island : part_.islands) island_clearances_.emplace_back(*island, reach_);
    }
}

void PartGuard::emit(const Event& event) {
    if (violation_) return;
    // The refused move's movement and kind travel in its tag.
    auto refused = [&](const std::optional<CompError>& e) {
        if (!e || violation_) return;
        violation_ = Violation{movement_of(e->source), rapid_of(e->source), at_, "", e->message};
    };
    visit_exhaustive(overloaded{
                         [&](const Rapid& r) {
                             CompMove m;
                             m.kind = CompMove::Kind::rapid;
                             m.end = r.to;
                             m.source = tag(Movement::cutting, true);
                             refused(comp_.move(m));
                         },
                         [&](const Linear& l) {
                             CompMove m;
                             m.end = l.to;
                             m.source = tag(l.movement, false);
                             refused(comp_.move(m));
                         },
                         [&](const ThreadCycle& c) {
                             for (const Event& m : thread_cycle_moves(c)) emit(m);
                         },
                         [&](const TurnCycle& c) {
                             for (const Event& m : turn_cycle_moves(c)) emit(m);
                         },
                         [&](const FinishCycle& c) {
                             for (const Event& m : finish_cycle_moves(c, RoughCyclePattern::linuxcnc_g71)) emit(m);
                         },
                         [&](const GrooveCycle& c) {
                             for (const Event& m : groove_cycle_moves(c)) emit(m);
                         },
                         [&](const ThreadFeed& t) {
                             CompMove m;
                             m.end = t.to;
                             m.source = tag(Movement::cutting, false);
                             refused(comp_.move(m));
                         },
                         [&](const Arc& a) {
                             CompMove m{CompMove::Kind::arc, a.to, {a.centre.x, a.centre.y}, a.direction, a.turns};
                             m.source = tag(a.movement, false);
                             refused(comp_.move(m));
                         },
                         [&](const Compensation& c) {
                             if (c.side == CompensationSide::off)
                                 refused(comp_.off(tag(Movement::lead_out, false)));
                             else
                                 refused(comp_.on(c.side == CompensationSide::left ? CompSide::left : CompSide::right, c.radius,
                                                  tag(Movement::lead_in, false)));
                         },
                         [&](const OperationStart&) {}, [&](const OperationEnd&) {}, [&](const Comment&) {},
                         [&](const ToolChange&) { comp_.flush(); }, [&](const Spindle&) {}, [&](const Coolant&) {},
                         [&](const Dwell&) {}, [&](const DrillCycle&) { comp_.flush(); }, [&](const DrillPoint&) {}, [&](const DrillEnd&) {},
                         [&](const Stop&) { comp_.flush(); }, [&](const CustomBlock&) {},
                     },
                     event);
}

void PartGuard::check(const CompMove& m) {
    if (violation_) return;
    if (!known_) {
        at_ = m.end;
        known_ = true;
        return;
    }
    const Vec3 from = at_;
    at_ = m.end;
    const Movement movement = movement_of(m.source);
    const bool rapid = rapid_of(m.source);
    const double tol = part_.tolerance;
    const double low = std::min(from.z, m.end.z);
    auto fail = [&](Vec3 where, std::string what) {
        violation_ = Violation{movement, rapid, where, std::move(what), ""};
    };
    if (low < floor_ - tol) {
        fail(from.z < m.end.z ? from : m.end,
             fmt::format("goes down to Z{}, below the floor it may reach (Z{})", show(low), show(floor_)));
        return;
    }
    if (low >= part_.top_z - tol) {
        side_known_ = false;
        island_side_known_ = false;
        return;
    }
    PathPiece piece{{from.x, from.y}, {{m.end.x, m.end.y}, std::nullopt, m.direction}};
    if (m.kind == CompMove::Kind::arc) piece.segment.centre = m.centre;
    ClosestApproach near = clearance_.nearest(piece);
    for (const ProfileClearance& island : island_clearances_)
        if (const ClosestApproach c = island.nearest(piece); c.distance < near.distance) near = c;
    const double need = part_.tool_radius + wall_;
    // Z where the closest point is: along the move (the end's Z for a point).
    const double len = std::hypot(m.end.x - from.x, m.end.y - from.y);
    const double t = len > 0 ? std::clamp(std::hypot(near.at.x - from.x, near.at.y - from.y) / len, 0.0, 1.0) : 1.0;
    const Vec3 where{near.at.x, near.at.y, from.z + (m.end.z - from.z) * t};
    if (near.distance < need - tol) {
        // The nearest point of the profile says how far; which side of it the centre is says
        // whether that is the depth of the cut or what is left of the tool's reach.
        const Vec2 at{where.x, where.y};
        bool in_material = part_.material_inside && clearance_.inside(at) == *part_.material_inside;
        for (const ProfileClearance& island : island_clearances_) in_material = in_material || island.inside(at);
        if (in_material) {
            fail(where, fmt::format("brings the tool centre inside the material the part keeps, {} mm from the profile at "
                                    "({}, {}, {}): it cuts {} mm into it (the centre must stay {} mm outside: tool radius {}{})",
                                    show(near.distance), show(where.x), show(where.y), show(where.z),
                                    show(need + near.distance), show(need), show(part_.tool_radius),
                                    wall_ > 0 ? " + " + show(wall_) + " stock" : ""));
            return;
        }
        fail(where, fmt::format("brings the tool centre {} mm from the profile at ({}, {}, {}): it cuts {} mm into what the part "
                                "keeps (the centre must stay {} mm away: tool radius {}{})",
                                show(near.distance), show(where.x), show(where.y), show(where.z), show(need - near.distance),
                                show(need), show(part_.tool_radius), wall_ > 0 ? " + " + show(wall_) + " stock" : ""));
        return;
    }
    if (part_.material_inside && !side_known_) {
        const Vec2 p{from.x, from.y};
        if (clearance_.inside(p) == *part_.material_inside) {
            fail(from, fmt::format("puts the tool centre at ({}, {}, {}), {} the profile: in the material", show(from.x),
                                   show(from.y), show(std::min(from.z, m.end.z)),
                                   *part_.material_inside ? "inside" : "outside"));
            return;
        }
        side_known_ = true;
    }
    if (!island_clearances_.empty() && !island_side_known_) {
        const Vec2 p{from.x, from.y};
        for (const ProfileClearance& island : island_clearances_)
            if (island.inside(p)) {
                fail(from, fmt::format("puts the tool centre at ({}, {}, {}), inside an island: in the material", show(from.x),
                                       show(from.y), show(std::min(from.z, m.end.z))));
                return;
            }
        island_side_known_ = true;
    }
}

}  // namespace camgen
