#pragma once
#include "camgen/post.hpp"

namespace camgen {

// Fanuc-style ISO post. Settings (machine file "settings"): programNumber (0: none),
// percentLines, toolLengthOffset (G43 H), toolChange (T M6), endCode.
class IsoPost : public Post {
public:
    IsoPost(const Machine& machine, std::ostream& out, PostOptions options);

protected:
    void on_open() override;
    void on_close() override;
    void on_tool_change(const ToolChange& tool) override;
    void on_spindle(const Spindle& spindle) override;
    void on_dwell(double seconds) override;
    void on_rapid(const Vec3& to) override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec, Vec2 at, bool first) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;

    int program_number_ = 1000;
    bool percent_ = true;
    bool length_offset_ = true;
    bool tool_change_ = true;
    std::string end_code_ = "M30";
    bool length_offset_pending_ = false;
};

}  // namespace camgen
