#pragma once
// The ISO lathe post (dialect "iso-lathe": linuxcnc-lathe, fanuc-lathe): the ISO post in the
// XZ plane, with what lathes write differently. Its settings are iso::LatheSettings: the ISO
// ones and its own, drillingPlane (true: the canned cycle runs under G17, so that it drills
// along Z, and G18 follows it - LinuxCNC; false: no plane word - Fanuc T), toolCall ("m6": the
// ISO tool change; "turret": T0101, tool and offset number), spindleLimit (true: G50 S<maxRpm>
// before the first spindle start, and G97 S.. M3). A cycle of style "fanuc-g74" is Fanuc T's
// two-block peck drilling G74 R(e) / G74 Z Q(least increments) F.
#include <vector>

#include "machines/iso/iso_post.hpp"
#include "machines/iso/fanuc_g76.hpp"
#include "machines/iso/fanuc_g75.hpp"
#include "machines/iso/linuxcnc_g76.hpp"

namespace camgen {

class IsoLathePost : public IsoPost {
public:
    IsoLathePost(const Machine& machine, std::ostream& out, PostOptions options);

protected:
    void on_open() override;
    void on_tool_change(const ToolChange& tool) override;
    // G97 S.. M3 (Fanuc T after G50 S<maxRpm>; LinuxCNC's G97 only after a G96), or constant
    // surface speed: G50 S<limit> G96 S<vc> M3 (Fanuc T), G96 D<limit> S<vc> M3 (LinuxCNC).
    void on_spindle(const Spindle& spindle) override;
    std::optional<std::string> surface_speed_refusal() const override { return std::nullopt; }
    // G33 Z K (LinuxCNC) or G32 Z F (Fanuc T), the threadMove setting; along Z only.
    void on_thread_feed(const Vec3& from, const ThreadFeed& move) override;
    std::optional<std::string> canned_limit(const DrillCycle& cycle, const DrillingCycleSpec& spec) const override;
    void on_drilling_header(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    void on_drilling_point(const DrillCycle& cycle, const DrillingCycleSpec& spec, Vec2 at, bool first) override;
    void on_drilling_footer(const DrillCycle& cycle, const DrillingCycleSpec& spec) override;
    // Fanuc T system A: G98/G99 are the feed modes, and a drilling cycle returns to the Z it
    // started from (the retract plane, where the header put the tool).
    bool writes_return_level() const override;
    // Nose-radius compensation (G41/G42 in G18): a comment naming what the control's table must
    // hold (LinuxCNC: the tool table's D, the nose diameter, and Q, the orientation; Fanuc T: the
    // offset's R and imaginary tip T), then G41/G42 without a D word on the next feed move.
    void on_compensation(const Compensation& compensation) override;
    std::string compensation_words(const Compensation& compensation) const override;
    // LinuxCNC's G76 P Z I J K R Q H from the drive point (linuxcnc_g76.hpp), or Fanuc T's
    // two-block G76 from the start point (fanuc_g76.hpp).
    void on_thread_cycle(const ThreadCycle& cycle, const ThreadingCycleSpec& spec) override;
    std::optional<std::string> thread_cycle_limit(const ThreadCycle& cycle, const ThreadingCycleSpec& spec) const override;
    // LinuxCNC's G71 (G72 along X): the profile as a subroutine o<n> sub ... o<n> endsub just
    // before it, then G71 (G72) Q<n> D0 I R F from the start point. Its limit: the control's moves
    // from the rounded words (linuxcnc_g7x) must be the cycle's within 0.001 mm.
    void on_turn_cycle(const TurnCycle& cycle, const RoughingCycleSpec& spec) override;
    std::optional<std::string> turn_cycle_limit(const TurnCycle& cycle, const RoughingCycleSpec& spec) const override;
    // Fanuc T's G75 R(e) / G75 X Z P Q F from the cycle's start (fanuc_g75.hpp).
    void on_groove_cycle(const GrooveCycle& cycle, const GroovingCycleSpec& spec) override;
    std::optional<std::string> groove_cycle_limit(const GrooveCycle& cycle, const GroovingCycleSpec& spec) const override;

private:
    // The G76 words of a cycle, as text, and the values the control reads from them.
    struct G76Words {
        std::vector<std::string> text;
        iso::LinuxcncG76 read;
    };
    G76Words g76_words(const ThreadCycle& cycle) const;
    // The G71 subroutine's lines and the cycle as the control reads them back (rounded).
    struct G71Words {
        std::vector<std::string> sub;   // the profile's blocks
        Profile profile;                // as read back, (Z, radius)
        Vec2 start;
        double depth = 0.0, retract = 0.0;
        std::string i, r;               // the I and R words
    };
    G71Words g71_words(const TurnCycle& cycle) const;
    int next_sub_ = 100;          // the number of the next profile subroutine
    // A profile's blocks after its start (G1 X Z, G2/G3 X Z I K), appended to `lines`, and the
    // profile as the control reads them back (`read`'s start set by the caller).
    void profile_blocks(const Profile& profile, std::vector<std::string>& lines, Profile& read) const;
    // Fanuc T's G71 type I: the start point A's X word, the first block's U R, the finishing
    // shape's blocks (ns: G0 X along X from A) and the cycle as the control reads it (rounded);
    // G72 (a cycle along X): A's Z word, W R, ns G0 Z along Z from A.
    struct FanucG71Words {
        std::string a_word, u, r;  // (u: G72's W)
        std::vector<std::string> shape;
        Profile read;             // the finishing shape, (Z, radius)
        Vec2 start;               // A, rounded
        double depth = 0.0, retract = 0.0;
        Vec2 allowance;           // (W, U/2) as written, rounded (a cycle linked to G70; else 0)
        std::string u_allow, w_allow;  // the second block's U and W
    };
    FanucG71Words fanuc_g71_words(const TurnCycle& cycle) const;
    std::optional<std::string> fanuc_g71_limit(const TurnCycle& cycle) const;
    void write_fanuc_g71(const TurnCycle& cycle, const RoughingCycleSpec& spec);
    long next_shape_number_ = 1;  // the next ns where the program has no sequence numbers
    // The last roughing cycle written linked to a G70 (CycleFinish): the turn-profile's path and
    // its shape's ns, nf.
    struct LinkedShape {
        std::string finishing_path;
        long ns = 0, nf = 0;
    };
    std::optional<LinkedShape> linked_;
    std::optional<std::string> finish_cycle_limit(const FinishCycle& cycle) const override;
    void on_finish_cycle(const FinishCycle& cycle) override;
    // Fanuc T's two blocks, or why the cycle cannot be written so.
    struct FanucG76Words {
        std::vector<std::string> first, second;
        iso::FanucG76 read;
        std::string refusal;
    };
    FanucG76Words fanuc_g76_words(const ThreadCycle& cycle) const;
    // The G75 words of a grooving cycle (G74's of a face groove): the first block's R(e), the
    // second's words, and the values the control reads from them.
    struct GrooveWords {
        std::string back_off;
        std::vector<std::string> text;
        iso::FanucGroove read;
    };
    GrooveWords groove_words(const GrooveCycle& cycle) const;
    const iso::LatheSettings& lathe_;
    double limit_written_ = 0.0;  // the G50 S written last (rpm), 0: none
    bool surface_mode_ = false;   // G96 is in effect (M5 leaves it so): an rpm needs G97
};

}  // namespace camgen
