#include "camgen/geometry/offset.hpp"
#include "camgen/geometry/vec.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/geometry/curve.hpp"

// The offset of one profile: the classical offset of src/geometry/curve.hpp over its one loop
// (open or closed), the longest path first, notes by segment.

namespace camgen {

OffsetSide side_for(Orientation orientation, Region region) {
    const bool left = (orientation == Orientation::ccw) == (region == Region::inside);
    return left ? OffsetSide::left : OffsetSide::right;
}

OffsetResult offset_profile(const Profile& profile, double d, OffsetSide side) {
    if (!(d > 0.0)) {  // no offset: the profile itself
        OffsetResult same{profile, {}, {}, {}};
        for (std::size_t i = 0; i < profile.segments.size(); ++i) same.source.push_back(i);
        return same;
    }
    using curves::chain, curves::chain_gap, curves::Curve, curves::Element, curves::elements_of, curves::KeptPiece, curves::LoopSpan,
        curves::min_piece, curves::mm_text, curves::OffsetPath, curves::OffsetPieces, curves::path_of, curves::RawPiece, curves::same_length;
    const double s = side == OffsetSide::left ? 1.0 : -1.0;
    const bool closed = is_closed(profile);
    const std::vector<Element> elements = elements_of(profile);
    OffsetResult result;
    result.profile = Profile{profile.plane, profile.start, {}};

    // Concave arcs tighter than the distance.
    for (std::size_t i = 0; i < elements.size(); ++i) {
        const Curve& k = elements[i].curve;
        if (k.arc && k.r < d - same_length && (k.sweep > 0) == (s > 0))
            result.notes.push_back({OffsetNoteKind::arc_too_tight, elements[i].segment,
                                    "segment " + std::to_string(elements[i].segment) + ": a concave arc of radius " + mm_text(k.r) +
                                        " mm is tighter than the offset " + mm_text(d) + " mm; the tool cannot reach into it"});
    }
    const OffsetPieces pieces = offset_pieces(elements, {LoopSpan{0, elements.size(), closed}}, d, s);
    const std::vector<RawPiece>& raw = pieces.raw;
    const std::vector<KeptPiece>& kept = pieces.kept;
    // Per input segment: an arc off its circle is two elements, and kept when either is.
    std::vector<bool> segment_kept(profile.segments.size(), false);
    for (const KeptPiece& k : kept)
        if (raw[k.raw].element && k.curve.length() >= min_piece) segment_kept[elements[*raw[k.raw].element].segment] = true;

    for (std::size_t i = 0; i < raw.size(); ++i) {
        const auto& e = raw[i].element;
        if (!e || segment_kept[elements[*e].segment]) continue;
        const bool noted = std::any_of(result.notes.begin(), result.notes.end(), [&](const OffsetNote& n) {
            return n.segment == elements[*e].segment;
        });
        if (!noted)
            result.notes.push_back({OffsetNoteKind::element_removed, elements[*e].segment,
                                    "segment " + std::to_string(elements[*e].segment) +
                                        ": its offset vanishes, the tool cannot follow it (cut away by its neighbours)"});
    }

    std::vector<OffsetPath> paths;
    for (const auto& c : chain(kept)) {
        double length = 0.0;
        for (std::size_t i : c) length += kept[i].curve.length();
        if (length < chain_gap) continue;  // a crumb where pieces cross
        // Only a chain that comes round to its start has its end put on it: moving the end of
        // a chain that does not would bend its last arc off its circle.
        const bool comes_round = closed && distance(kept[c.back()].curve.b, kept[c.front()].curve.a) <= chain_gap;
        OffsetPath p = path_of(c, kept, raw, elements, profile.plane, comes_round);
        // A closed path enclosing nothing is a slit where the tool exactly fits between two
        // sides: the region beyond the distance is empty there.
        const bool slit = comes_round && enclosed_area(p.profile) < chain_gap * p.length;
        if (p.length >= chain_gap && !p.profile.segments.empty() && !slit) paths.push_back(std::move(p));
    }
    if (paths.empty()) {
        // What vanished on the way is no news then.
        result.notes.clear();
        result.notes.push_back({OffsetNoteKind::consumed, std::nullopt,
                                "nothing remains of the profile offset by " + mm_text(d) + " mm: it is smaller than the tool"});
        return result;
    }
    const auto longest = std::max_element(paths.begin(), paths.end(), [](const OffsetPath& a, const OffsetPath& b) { return a.length < b.length; });
    result.profile = longest->profile;
    result.source = longest->source;
    for (auto it = paths.begin(); it != paths.end(); ++it)
        if (it != longest) result.others.push_back(it->profile);
    if (!result.others.empty())
        result.notes.push_back({OffsetNoteKind::split, std::nullopt,
                                "the offset by " + mm_text(d) + " mm falls apart into " + std::to_string(paths.size()) +
                                    " paths: the profile has a neck narrower than the tool"});
    return result;
}

ProfilePoint point_at(const Profile& profile, double length) {
    using curves::Curve, curves::curve_of;
    ProfilePoint out{profile.start, {1.0, 0.0}, 0};
    double walked = 0.0;
    for (std::size_t i = 0; i < profile.segments.size(); ++i) {
        const Curve k = curve_of(profile, i);
        const double l = k.length();
        if (l <= 0.0) continue;
        const double t = std::clamp((length - walked) / l, 0.0, 1.0);
        out = {t >= 1.0 ? k.b : k.at(t), k.tangent(t), i};
        if (length <= walked + l) return out;
        walked += l;
    }
    return out;
}

Profile sub_profile(const Profile& profile, double from, double to) {
    using curves::Curve, curves::curve_of, curves::same_length;
    if (from > to && is_closed(profile)) {
        Profile head = sub_profile(profile, from, profile_length(profile));
        const Profile tail = sub_profile(profile, 0.0, to);
        if (head.segments.empty()) return tail;
        head.segments.insert(head.segments.end(), tail.segments.begin(), tail.segments.end());
        return head;
    }
    Profile out{profile.plane, point_at(profile, from).point, {}};
    double walked = 0.0;
    for (std::size_t i = 0; i < profile.segments.size(); ++i) {
        const Curve k = curve_of(profile, i);
        const double l = k.length();
        const double t0 = std::clamp((from - walked) / l, 0.0, 1.0), t1 = std::clamp((to - walked) / l, 0.0, 1.0);
        walked += l;
        if (l <= 0.0 || (t1 - t0) * l <= same_length) continue;
        const ProfileSegment& s = profile.segments[i];
        if (out.segments.empty()) out.start = t0 <= 0.0 ? k.a : k.at(t0);
        out.segments.push_back({t1 >= 1.0 ? s.end : k.at(t1), s.centre, s.direction});
    }
    return out;
}

double distance_to(const Profile& profile, Vec2 p) {
    using curves::Curve, curves::curves_of, curves::distance_to_curve;
    if (profile.segments.empty()) return distance(profile.start, p);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < profile.segments.size(); ++i)
        for (const Curve& k : curves_of(profile, i)) best = std::min(best, distance_to_curve(k, p));
    return best;
}

}  // namespace camgen
