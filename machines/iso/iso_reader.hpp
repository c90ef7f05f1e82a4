#pragma once
// The ISO reader (Fanuc-style programs: fanuc, linuxcnc, grbl) and its factories, for the
// dialect registry (machines/registry.cpp). Its lathe variant (iso_lathe_reader.cpp) extends
// it through the hooks below: the codes, words and cycles only a lathe has.
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camgen/post/machine.hpp"
#include "machines/iso/iso_settings.hpp"
#include "src/reader/nc_reader.hpp"

namespace camgen::reader {

// A reader of ISO programs for `machine`; `source` names the program in messages.
std::unique_ptr<NcReader> make_iso_reader(const Machine& machine, std::string source);
// The same for the iso-lathe dialect.
std::unique_ptr<NcReader> make_iso_lathe_reader(const Machine& machine, std::string source);

// A tool change announced by a comment, to be made by the M0 on the next line (GRBL).
struct IsoInsertTool {
    int number = 0;
    std::string description;
    int line = 0;
};

class IsoReader : public NcReader {
public:
    IsoReader(const Machine& machine, std::string source, const iso::Settings& settings);
    std::vector<std::pair<std::string, std::string>> modal_state() const override;

protected:
    // The G and M codes of one block, by modal group, as block() collects them.
    struct BlockCodes {
        std::optional<Code> motion, plane, units, feed_mode, comp, length_offset, return_level, dwell, work_offset;
        std::optional<Code> coolant, machine_coords, spindle_mode;
        MCodes m;
    };

    bool frame_line(std::string_view line) override { return line == "%"; }
    void line(std::string_view text) override;
    void block(const Block& b) override;
    void finish() override;

    // A variant's hooks. A G code the base does not know (a lathe's G50/G97): taken into
    // `codes` (true), or unknown (false).
    virtual bool variant_code(BlockCodes& codes, const Word& x, Code c);
    // The address letters of a block (a dialect's own added: Fanuc T G71's U and W, LinuxCNC G76's E
    // and L).
    virtual std::string_view address_letters() const { return "XYZIJKRQPFSTHD"; }
    // The block's words before its S is read as a speed (Fanuc T's G50 S is a limit).
    virtual void variant_words(const BlockCodes& codes, BlockWords& w);
    // The block's T word, if the variant calls tools otherwise (a turret's T0101): true if taken.
    virtual bool variant_tool_call(const Word& t);
    // A canned cycle of a style only the variant writes (Fanuc T's G74): true if read.
    virtual bool variant_cycle(const DrillingCycleSpec& spec, BlockWords& w);
    // Refuses a canned cycle that would drill along another axis than Z in the current plane (one
    // not under G17; a lathe variant whose post writes no plane word lets it be).
    virtual void check_cycle_plane(const std::string& name) const;
    // Refuses G41/G42 (`g`) outside the plane camgen compensates in: G17 on a mill, G18 on a lathe.
    void check_comp_plane(const Word& g) const;
    // A motion mode only the variant has (a lathe's thread-cutting G33/G32): its block read, true.
    virtual bool variant_motion(int mode, BlockWords& w);
    // Whether a block in motion mode `mode` takes F as its lead, not as a feed (Fanuc T's G32).
    virtual bool f_is_lead(int mode) const;

    void set_group(std::optional<Code>& group, Code c) const { NcReader::set_group(group, c, "modal group"); }
    Plane plane() const { return plane_; }

private:
    // The block's G and M codes by group; its other words go into `w`.
    BlockCodes block_codes(const Block& b, BlockWords& w);
    void motion_block(int mode, BlockWords& w);
    void cycle_block(int g, BlockWords& w);
    void rigid_tap(BlockWords& w);
    const DrillingCycleSpec* canned_spec(int g) const;
    bool pauses_for_tools() const { return settings_.tool_change == iso::ToolChangeStyle::pause; }
    // GRBL's tool change: a comment "Insert tool <n>: ..." and M0 on the next line.
    std::optional<IsoInsertTool> insert_tool(const std::string& comment) const;
    void announce_tools(const Block& b);
    void refuse_tool_words(const Word* t, const BlockCodes& codes) const;

    const iso::Settings& settings_;
    std::optional<IsoInsertTool> pending_insert_;
    int motion_ = -1;  // the modal motion code (tenths); -1: none yet
    Plane plane_ = Plane::xy;
    bool comp_on_ = false;          // G41/G42 in force
    bool x_mode_selected_ = false;  // G7/G8 read (LinuxCNC's lathe diameter mode), or none to read
    bool g98_ = true;  // return to the initial level (LinuxCNC's default)
    std::optional<double> cycle_r_, cycle_z_, cycle_q_, cycle_p_;
    std::optional<double> initial_z_;  // Z when the current run of cycle blocks began
    std::optional<int> selected_tool_;
    std::string length_offset_ = "none";  // "G43 H1", "G49": the tool length offset selected last
    int program_numbers_ = 0;             // O lines read
    bool ended_ = false;
};

}  // namespace camgen::reader
