#include "camgen/stats.hpp"

#include <cmath>

#include <fmt/format.h>

#include "camgen/arcs.hpp"

namespace camgen {

void StatsSink::move_to(const Vec3& to, bool rapid) {
    if (known_) {
        const double dx = to.x - pos_.x, dy = to.y - pos_.y, dz = to.z - pos_.z;
        const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
        if (rapid) {
            stats_.rapid_length += d;
            stats_.rapid_xy_length += std::hypot(dx, dy);
        } else {
            stats_.feed_length += d;
        }
    }
    pos_ = to;
    // After a tool change the position is unknown: the first rapid is not counted.
    known_ = true;
}

void StatsSink::emit(const Event& event) {
    if (const auto* r = std::get_if<Rapid>(&event)) {
        move_to(r->to, true);
    } else if (const auto* l = std::get_if<Linear>(&event)) {
        move_to(l->to, false);
    } else if (const auto* a = std::get_if<Arc>(&event)) {
        if (known_) {
            ArcGeometry g = resolve_arc(pos_, *a);
            PlanePoint s = to_plane(g.start, a->plane), e = to_plane(g.end, a->plane);
            stats_.feed_length += std::hypot(g.radius * g.sweep, e.w - s.w);
        }
        pos_ = a->to;
    } else if (std::holds_alternative<ToolChange>(event)) {
        known_ = false;
    } else if (const auto* c = std::get_if<DrillCycle>(&event)) {
        cycle_ = *c;
    } else if (const auto* p = std::get_if<DrillPoint>(&event)) {
        ++stats_.holes;
        if (cycle_ && known_)
            for (const Event& e : longhand_moves(*cycle_, pos_, p->at, longhand_)) emit(e);
    } else if (std::holds_alternative<DrillEnd>(event)) {
        cycle_.reset();
    }
}

std::string format_stats(const PathStats& s) {
    return fmt::format("rapid {:.1f} mm (XY {:.1f} mm), feed {:.1f} mm, {} hole{}", s.rapid_length, s.rapid_xy_length,
                       s.feed_length, s.holes, s.holes == 1 ? "" : "s");
}

}  // namespace camgen
