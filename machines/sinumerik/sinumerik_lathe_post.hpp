#pragma once
// The Sinumerik lathe post (dialect "sinumerik-lathe"): the Sinumerik post in G18 (the start
// block's DIAMON makes X a diameter), with axial drilling as Autodesk's Siemens mill-turn post
// writes it: G17, MCALL CYCLE8x(...) at X0, MCALL, back to G18.
#include "machines/sinumerik/sinumerik_post.hpp"

namespace camgen {

class SinumerikLathePost : public SinumerikPost {
public:
    SinumerikLathePost(const Machine& machine, std::ostream& out, PostOptions options);

protected:
    void on_open() override;
    // S.. M3 (G97 S.. M3 after a G96), or constant surface speed: LIMS=<limit> (when it
    // changes), then G96 S<vc> M3.
    void on_spindle(const Spindle& spindle) override;
    std::optional<std::string> surface_speed_refusal() const override { return std::nullopt; }
    // G33 Z K: K the lead along Z (Siemens 840D sl programming manual, fundamentals: "Thread
    // cutting with constant lead (G33)"); along Z only.
    void on_thread_feed(const Vec3& from, const ThreadFeed& move) override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    // CYCLE83's full retract comes back by the machine's _DIS1: another peckClearance cannot be written.
    std::optional<std::string> canned_limit(const DrillCycle& cycle, const DrillingCycleSpec& spec) const override;
    // Nose-radius compensation: a comment naming the radius and cutting edge position D1 must
    // hold, then G41/G42 (the edge selected with the tool).
    void on_compensation(const Compensation& compensation) override;

private:
    double limit_written_ = 0.0;  // the LIMS= written last (rpm), 0: none
    bool surface_mode_ = false;   // G96 is in effect: an rpm needs G97
};

}  // namespace camgen
