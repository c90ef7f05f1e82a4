#pragma once
// The part-aware safety check of the milling operations that cut beside a profile (issue 24):
// an EventSink that takes an operation's events, applies G41/G42 as the control does
// (CutterCompensation, LinuxCNC's rules), and checks every tool-centre position below the stock
// top against the part: the tool must stay outside the material by the stock it must keep (the
// radius plus stockToLeave, plus the finishing allowance while roughing), on the air side of a
// closed profile, and not below the floor it may reach. The first move that breaks a rule is
// kept as a Violation naming the move (lead-in, ramp, ...), where it is and by how much; a
// program the control would refuse is one too. Lengths mm.
#include <optional>
#include <string>
#include <vector>

#include "camgen/events/events.hpp"
#include "camgen/geometry/clearance.hpp"
#include "camgen/geometry/compensation.hpp"

namespace camgen {

// What the tool must keep clear of.
struct GuardedPart {
    const Profile* profile = nullptr;       // the part's edge as drawn, XY
    std::optional<bool> material_inside;    // closed profiles: the material is inside (an outline)
                                            // or outside (a pocket); open ones: unset (the band
                                            // beside the profile is checked, not a side)
    std::vector<const Profile*> islands;    // closed profiles whose material is inside (a pocket's
                                            // islands), kept as the profile is
    double tool_radius = 0.0;
    double top_z = 0.0;                     // the stock top: above it nothing is checked
    double tolerance = 0.003;               // 0.002 mm plus the output resolution
};

struct Violation {
    Movement movement = Movement::cutting;
    bool rapid = false;
    Vec3 at;
    std::string what;   // the sentence: "brings the tool centre 2.000 mm from the profile at ..."
    std::string control_refuses;  // set: the control's own refusal (G41/G42)
};

class PartGuard : public EventSink {
public:
    explicit PartGuard(const GuardedPart& part);
    // The stock the following moves must keep on the wall (stockToLeave, plus the finishing
    // allowance while roughing), and the lowest Z they may reach.
    void keep(double wall_stock, double floor_z);
    void emit(const Event& event) override;
    const std::optional<Violation>& violation() const { return violation_; }

private:
    void check(const CompMove& tool_move);
    GuardedPart part_;
    ProfileClearance clearance_;
    std::vector<ProfileClearance> island_clearances_;
    CutterCompensation comp_;
    double wall_ = 0.0, floor_ = -1e300;
    double reach_ = 0.0;   // what the clearance answers exactly, mm
    Vec3 at_;
    bool known_ = false;
    bool side_known_ = false;          // the last checked position was on the air side, no gap since
    bool island_side_known_ = false;   // the same for the islands
    std::optional<Violation> violation_;
};

// "lead-in", "ramp", ... for messages.
std::string movement_words(Movement m, bool rapid);

}  // namespace camgen
