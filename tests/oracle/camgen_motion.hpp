#pragma once
// camgen's own reading of a program in the oracle's normalised form (rs274.hpp's Step), so
// that what camgen's reader and trace make of a program can be compared with rs274's motion.
#include <map>
#include <string>
#include <vector>

#include "camgen/operations/registry.hpp"
#include "camgen/post/machine.hpp"
#include "rs274.hpp"

namespace camgen::oracle {

// The job posted for the machine, as `camgen JOB --machine M` writes it (its name as the
// program's).
std::string posted_program(const Job& job, const Machine& machine);

// The motion camgen's reader makes of a program: moves of zero length and zero dwells
// dropped, feeds and arcs with their rate, spindle entries on changes.
std::vector<Step> read_with_camgen(const std::string& program, const Machine& machine);

// A lathe program's moves as camgen reads them, as xz_moves gives rs274's: traverses, feeds and
// arcs, their ends in (X radius, Z) (the lead of a synchronised feed and where a move began are
// left 0).
std::vector<XzMove> camgen_xz_moves(const std::string& program, const Machine& machine);

// The same with G41/G42 applied as the control applies them, offset register -> radius from
// `radii` (mm): the tool centre's moves, or where the control refuses the program, camgen's
// line and message (the ControlRefusal's detail without "the control refuses this: ").
struct CompensatedRead {
    std::vector<Step> steps;
    int refused_line = 0;  // 0: not refused
    std::string refusal;
};
CompensatedRead read_with_camgen(const std::string& program, const Machine& machine, const std::map<int, double>& radii);

// Checks (doctest CHECKs) that camgen reads `program` as rs274 ran it (`theirs`), step for step
// from the first feed on (before it the two know the start differently: rs274 from its origin,
// camgen from the tool change): the same kinds, end points within `tolerance` mm, arcs' turns.
// `tolerance` (mm): rs274 prints positions to 4 decimals, so a diameter-mode program's X of an
// odd thousandth (a radius of half a thousandth) needs 1e-4.
void check_read_as_run(const std::vector<Step>& theirs, const std::string& program, const Machine& machine,
                       double tolerance = 1e-6);

}  // namespace camgen::oracle
