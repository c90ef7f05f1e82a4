// The history of a simulated part that the page's block slider replays (SimHistory).
#include "camgen/simulation/pictures.hpp"

#include <algorithm>
#include <cmath>

namespace camgen {

SimHistory::SimHistory(const SimResult& initial_result, std::size_t event_budget) : budget(std::max<std::size_t>(event_budget, 16)) {
    kind = initial_result.kind;
    if (kind == MachineKind::lathe) {
        const LatheProfile& p = initial_result.lathe;
        factor = std::max(1, (p.nz + 4 * coarse_side - 1) / (4 * coarse_side));
        nx = (p.nz + factor - 1) / factor, ny = 1;
        x0 = p.z0, cell = p.dz * factor;
        bottom = 0;
        initial.assign(2 * static_cast<std::size_t>(nx), 0.0f);
        for (int c = 0; c < nx; ++c) {
            float out = std::numeric_limits<float>::infinity(), bore = 0.0f;
            for (int k = c * factor; k < std::min(p.nz, (c + 1) * factor); ++k) {
                out = std::min(out, static_cast<float>(p.outside[static_cast<std::size_t>(k)]));
                bore = std::max(bore, static_cast<float>(p.bore[static_cast<std::size_t>(k)]));
                top = std::max(top, p.outside[static_cast<std::size_t>(k)]);
            }
            initial[static_cast<std::size_t>(c)] = out, initial[static_cast<std::size_t>(nx + c)] = bore;
        }
        quantum = std::max(top, 1e-3) / 256;
    } else {
        const HeightField& f = initial_result.field;
        field_nx_ = f.nx;
        factor = std::max(1, (std::max(f.nx, f.ny) + coarse_side - 1) / coarse_side);
        nx = (f.nx + factor - 1) / factor, ny = (f.ny + factor - 1) / factor;
        x0 = f.x0, y0 = f.y0, cell = f.cell * factor;
        top = f.top, bottom = f.bottom;
        initial.assign(static_cast<std::size_t>(nx) * ny, static_cast<float>(f.top));
        for (int j = 0; j < f.ny; ++j)
            for (int i = 0; i < f.nx; ++i) {
                float& c = initial[static_cast<std::size_t>(j / factor) * nx + static_cast<std::size_t>(i / factor)];
                c = std::min(c, f.heights[static_cast<std::size_t>(j) * f.nx + i]);
            }
        quantum = std::max(top - bottom, 1e-3) / 256;
    }
    current_ = initial;
    logged_ = initial;
    current_line_.assign(static_cast<std::size_t>(nx) * ny, 0);
}

void SimHistory::lowered(std::size_t cell_index, float height, int line) {
    const std::size_t i = cell_index % static_cast<std::size_t>(field_nx_), j = cell_index / static_cast<std::size_t>(field_nx_);
    const std::size_t c = j / static_cast<std::size_t>(factor) * static_cast<std::size_t>(nx) + i / static_cast<std::size_t>(factor);
    if (!(height < current_[c])) return;
    current_[c] = height;
    current_line_[c] = line;
    if (logged_[c] - height >= quantum) log(c, line, height, 0.0f);
}

void SimHistory::turned(int sample, double outside, double bore, int line) {
    const std::size_t c = static_cast<std::size_t>(sample / factor), n = static_cast<std::size_t>(nx);
    const auto out = static_cast<float>(outside), in = static_cast<float>(bore);
    bool changed = false;
    if (out < current_[c]) current_[c] = out, changed = true;
    if (in > current_[n + c]) current_[n + c] = in, changed = true;
    if (!changed) return;
    current_line_[c] = line;
    if (logged_[c] - current_[c] >= quantum || current_[n + c] - logged_[n + c] >= quantum)
        log(c, line, current_[c], current_[n + c]);
}

void SimHistory::log(std::size_t c, int line, float value, float value2) {
    events.push_back({static_cast<std::int32_t>(c), line, value, value2});
    logged_[c] = value;
    if (kind == MachineKind::lathe) logged_[static_cast<std::size_t>(nx) + c] = value2;
    if (events.size() > budget) thin();
}

// Doubles the quantum until the log is within three quarters of its budget, replaying it from
// the initial part.
void SimHistory::thin() {
    const std::size_t n = static_cast<std::size_t>(nx);
    while (events.size() > budget * 3 / 4) {
        quantum *= 2;
        logged_ = initial;
        std::size_t kept = 0;
        for (const Event& e : events) {
            const auto c = static_cast<std::size_t>(e.cell);
            const bool keep = kind == MachineKind::lathe
                                  ? logged_[c] - e.value >= quantum || e.value2 - logged_[n + c] >= quantum
                                  : logged_[c] - e.value >= quantum;
            if (!keep) {
                ++thinned;
                continue;
            }
            logged_[c] = e.value;
            if (kind == MachineKind::lathe) logged_[n + c] = e.value2;
            events[kept++] = e;
        }
        events.resize(kept);
    }
}

void SimHistory::finish(const SimResult&) {
    const std::size_t n = static_cast<std::size_t>(nx);
    for (std::size_t c = 0; c < static_cast<std::size_t>(nx) * ny; ++c) {
        const bool differs = kind == MachineKind::lathe ? current_[c] != logged_[c] || current_[n + c] != logged_[n + c]
                                                        : current_[c] != logged_[c];
        if (!differs) continue;
        // Not through log(): the exact final values are never thinned away.
        events.push_back({static_cast<std::int32_t>(c), current_line_[c], current_[c],
                          kind == MachineKind::lathe ? current_[n + c] : 0.0f});
        logged_[c] = current_[c];
        if (kind == MachineKind::lathe) logged_[n + c] = current_[n + c];
    }
    final = current_;
}

}  // namespace camgen
