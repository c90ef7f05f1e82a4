#pragma once
// The ISO lathe post (dialect "iso-lathe": linuxcnc-lathe, fanuc-lathe): the ISO post in the
// XZ plane, with what lathes write differently. Its own settings (machine file "settings",
// beside the ISO ones): drillingPlane (true: the canned cycle runs under G17, so that it
// drills along Z, and G18 follows it - LinuxCNC; false: no plane word - Fanuc T), toolCall
// ("m6": the ISO tool change; "turret": T0101, tool and offset number), spindleLimit (true:
// G50 S<maxRpm> before the first spindle start, and G97 S.. M3). A cycle of style
// "fanuc-g74" is Fanuc T's two-block peck drilling G74 R(e) / G74 Z Q(least increments) F.
#include <nlohmann/json.hpp>

#include "machines/iso/iso_post.hpp"

namespace camgen {

namespace iso {
// The machine as the ISO post reads it (without the lathe's own settings) and those settings:
// held in a base that is built before IsoPost, which reads the machine in its constructor.
struct LatheMachine {
    explicit LatheMachine(const Machine& machine);
    Machine iso_machine;
    nlohmann::json lathe_settings = nlohmann::json::object();
};
}  // namespace iso

class IsoLathePost : private iso::LatheMachine, public IsoPost {
public:
    IsoLathePost(const Machine& machine, std::ostream& out, PostOptions options);

protected:
    void on_open() override;
    void on_tool_change(const ToolChange& tool) override;
    void on_spindle(const Spindle& spindle) override;
    std::optional<std::string> canned_limit(const DrillCycle& cycle, const DrillingCycleSpec& spec) const override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec, Vec2 at, bool first) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    // Fanuc T system A: G98/G99 are the feed modes, and a drilling cycle returns to the Z it
    // started from (the retract plane, where the header put the tool).
    bool writes_return_level() const override;

private:
    bool drilling_plane_ = true;
    iso::LatheToolCall tool_call_ = iso::LatheToolCall::m6;
    bool spindle_limit_ = false;
    bool limit_written_ = false;  // G50 S was written
};

}  // namespace camgen
