#pragma once
// The Sinumerik standard drilling cycles as the post writes them and the reader reads them
// back: each cycle's name and the position of every parameter in its call. The parameter
// orders of the standard cycles:
//   CYCLE81(RTP, RFP, SDIS, DP, DPR)
//   CYCLE82(RTP, RFP, SDIS, DP, DPR, DTB)
//   CYCLE83(RTP, RFP, SDIS, DP, DPR, FDEP, FDPR, DAM, DTB, DTS, FRF, VARI, _AXN, _MDEP, _VRT,
//           _DTD, _DIS1)
//   CYCLE84(RTP, RFP, SDIS, DP, DPR, DTB, SDAC, MPIT, PIT, POSS, SST, SST1)
//   CYCLE85(RTP, RFP, SDIS, DP, DPR, DTB, FFR, RFF)
//   CYCLE86(RTP, RFP, SDIS, DP, DPR, DTB, SDIR, RPA, RPO, RPAP, POSS)
//   CYCLE89(RTP, RFP, SDIS, DP, DPR, DTB)
#include <cstddef>
#include <string_view>

#include "camgen/vocabulary/vocabulary.hpp"

namespace camgen::sinumerik {

// A standard drilling cycle: its name and how many parameters its call takes.
struct CycleForm {
    std::string_view name;
    std::size_t count;
};

// The positions every drilling cycle shares: retract plane, reference plane, safety distance
// (from RFP), final depth (absolute) and final depth relative to RFP.
namespace common {
inline constexpr std::size_t rtp = 0, rfp = 1, sdis = 2, dp = 3, dpr = 4;
}  // namespace common

// CYCLE81 drilling.
namespace cycle81 {
inline constexpr CycleForm form{"CYCLE81", 5};
}  // namespace cycle81

// CYCLE82 drilling with a dwell at the bottom.
namespace cycle82 {
inline constexpr std::size_t dtb = 5;
inline constexpr CycleForm form{"CYCLE82", 6};
}  // namespace cycle82

// CYCLE83 deep-hole drilling.
namespace cycle83 {
inline constexpr std::size_t fdep = 5, fdpr = 6, dam = 7, dtb = 8, dts = 9, frf = 10, vari = 11, axn = 12, mdep = 13,
                             vrt = 14, dtd = 15, dis1 = 16;
inline constexpr CycleForm form{"CYCLE83", 17};
}  // namespace cycle83

// CYCLE84 rigid tapping.
namespace cycle84 {
inline constexpr std::size_t dtb = 5, sdac = 6, mpit = 7, pit = 8, poss = 9, sst = 10, sst1 = 11;
inline constexpr CycleForm form{"CYCLE84", 12};
}  // namespace cycle84

// CYCLE85 reaming.
namespace cycle85 {
inline constexpr std::size_t dtb = 5, ffr = 6, rff = 7;
inline constexpr CycleForm form{"CYCLE85", 8};
}  // namespace cycle85

// CYCLE86 boring with a spindle stop.
namespace cycle86 {
inline constexpr std::size_t dtb = 5, sdir = 6, rpa = 7, rpo = 8, rpap = 9, poss = 10;
inline constexpr CycleForm form{"CYCLE86", 11};
}  // namespace cycle86

// CYCLE89 boring with a dwell at the bottom.
namespace cycle89 {
inline constexpr std::size_t dtb = 5;
inline constexpr CycleForm form{"CYCLE89", 6};
}  // namespace cycle89

// Every cycle camgen writes and reads.
inline constexpr CycleForm cycle_forms[] = {cycle81::form, cycle82::form, cycle83::form, cycle84::form,
                                            cycle85::form, cycle86::form, cycle89::form};

// The cycle that drills a cycle kind.
constexpr const CycleForm& cycle_form(CycleKind kind) {
    switch (kind) {
        case CycleKind::drill: return cycle81::form;
        case CycleKind::dwell: return cycle82::form;
        case CycleKind::deep:
        case CycleKind::chip_break: return cycle83::form;
        case CycleKind::tap:
        case CycleKind::tap_left: return cycle84::form;
        case CycleKind::ream: return cycle85::form;
        case CycleKind::bore_stop: return cycle86::form;
        case CycleKind::bore_dwell: return cycle89::form;
    }
    return cycle81::form;
}

}  // namespace camgen::sinumerik
