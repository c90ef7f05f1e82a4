#pragma once
// Path statistics of a job's events (`camgen --stats`): how far the tool travels at rapid
// and at feed, drilling cycles counted with the moves they make (longhand_moves).
#include <string>

#include "camgen/events.hpp"
#include "camgen/longhand.hpp"

namespace camgen {

struct PathStats {
    double rapid_length = 0.0;     // mm, 3D length of rapid moves
    double rapid_xy_length = 0.0;  // mm, their length projected on XY
    double feed_length = 0.0;      // mm, feed moves and arcs (arcs by their length)
    long holes = 0;
};

// Sums the events it receives; forwards nothing. Arcs count by their true length.
class StatsSink : public EventSink {
public:
    explicit StatsSink(LonghandOptions longhand = {}) : longhand_(longhand) {}
    void emit(const Event& event) override;
    const PathStats& stats() const { return stats_; }

private:
    void move_to(const Vec3& to, bool rapid);
    LonghandOptions longhand_;
    PathStats stats_;
    Vec3 pos_;
    bool known_ = false;
    std::optional<DrillCycle> cycle_;
};

// "rapid 123.4 mm (XY 100.0 mm), feed 56.7 mm, 12 holes"
std::string format_stats(const PathStats& stats);

}  // namespace camgen
