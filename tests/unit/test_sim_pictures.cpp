// Pictures of the simulated part: the PNG read back with cairo (size, the colours of cut and
// uncut places, the section's profile), the STL read back (its triangle count as derived, closed
// and consistently oriented, its enclosed volume by the divergence theorem equal to the
// simulation's), the page's history replayed, and the CLI's rules for the output files.
#include <doctest/doctest.h>

#include <cairo.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "camgen/simulation/pictures.hpp"
#include "camgen/simulation/simulation.hpp"
#include "support.hpp"

namespace test_sim_pictures {

using namespace camgen;

constexpr double pi_ = 3.14159265358979323846;

Step feed(Vec3 a, Vec3 b, int line) {
    Step s;
    s.kind = StepKind::feed;
    s.from = a;
    s.to = b;
    s.tool = 1;
    s.line = line;
    s.feed = 300;
    return s;
}

ToolShape flat(double d) {
    ToolShape t;
    t.form = ToolForm::flat;
    t.diameter = d;
    return t;
}

// A 40 x 30 x 10 box at 0.1 mm: a pocket 4 deep cut by a 6 mm end mill in rows from
// (10, 10) to (30, 20) (so X 7..33, Y 7..23 after its radius), then a through hole at (35, 25).
// Lines: the pocket's rows 10.., the hole 100.
SimResult pocket_and_hole() {
    const Machine m = load_machine("linuxcnc");
    SimStock box;
    box.kind = SimStock::Kind::box;
    box.min = {0, 0, -10};
    box.max = {40, 30, 0};
    SimOptions o;
    o.resolution = 0.1;
    Simulator sim(m, box, {{1, flat(6)}}, o);
    int line = 10;
    for (double y = 10; y <= 20 + 1e-9; y += 2) sim.step(feed({10, y, -4}, {30, y, -4}, line++));
    sim.step(feed({35, 25, 1}, {35, 25, -11}, 100));
    sim.finish({});
    return sim.take();
}

// A PNG's pixels, decoded by cairo.
struct Decoded {
    int width = 0, height = 0;
    std::vector<std::uint32_t> px;
    Rgb at(double x, double y) const {
        const std::uint32_t v = px[static_cast<std::size_t>(std::floor(y)) * width + static_cast<std::size_t>(std::floor(x))];
        return {static_cast<int>((v >> 16) & 0xff), static_cast<int>((v >> 8) & 0xff), static_cast<int>(v & 0xff)};
    }
};

Decoded decode(const std::string& png) {
    REQUIRE(png.size() > 8);
    CHECK(png.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
    struct Reader {
        const std::string* data;
        std::size_t at = 0;
    } reader{&png};
    cairo_surface_t* s = cairo_image_surface_create_from_png_stream(
        [](void* closure, unsigned char* out, unsigned int length) {
            auto* r = static_cast<Reader*>(closure);
            if (r->at + length > r->data->size()) return CAIRO_STATUS_READ_ERROR;
            std::memcpy(out, r->data->data() + r->at, length);
            r->at += length;
            return CAIRO_STATUS_SUCCESS;
        },
        &reader);
    REQUIRE(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS);
    Decoded d;
    d.width = cairo_image_surface_get_width(s), d.height = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    for (int j = 0; j < d.height; ++j)
        for (int i = 0; i < d.width; ++i) {
            std::uint32_t v;
            std::memcpy(&v, data + static_cast<std::ptrdiff_t>(j) * stride + 4 * i, 4);
            d.px.push_back(v);
        }
    cairo_surface_destroy(s);
    return d;
}

// A triangle of a binary STL.
struct Tri {
    std::array<std::array<float, 3>, 3> v;
};

std::vector<Tri> read_stl(const std::string& bytes) {
    REQUIRE(bytes.size() >= 84);
    std::uint32_t n = 0;
    for (int k = 3; k >= 0; --k) n = (n << 8) | static_cast<unsigned char>(bytes[static_cast<std::size_t>(80 + k)]);
    REQUIRE(bytes.size() == 84 + 50 * static_cast<std::size_t>(n));
    CHECK(bytes.compare(0, 5, "solid") != 0);  // not mistaken for ASCII STL
    std::vector<Tri> out(n);
    for (std::uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) std::memcpy(&out[t].v[k][c], bytes.data() + 84 + 50 * t + 12 + 12 * k + 4 * c, 4);
    return out;
}

// The volume a closed, outward-oriented surface encloses (divergence theorem), and its area.
std::pair<double, double> volume_and_area(const std::vector<Tri>& tris) {
    double v = 0, area = 0;
    for (const Tri& t : tris) {
        const double ax = t.v[0][0], ay = t.v[0][1], az = t.v[0][2];
        const double bx = t.v[1][0], by = t.v[1][1], bz = t.v[1][2];
        const double cx = t.v[2][0], cy = t.v[2][1], cz = t.v[2][2];
        v += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6;
        const double ux = bx - ax, uy = by - ay, uz = bz - az, wx = cx - ax, wy = cy - ay, wz = cz - az;
        area += std::sqrt(std::pow(uy * wz - uz * wy, 2) + std::pow(uz * wx - ux * wz, 2) + std::pow(ux * wy - uy * wx, 2)) / 2;
    }
    return {v, area};
}

// Edge use by position: how many triangles use each undirected edge, and the balance of its
// two directions (0 for a consistently oriented closed surface). Returns {edges used by
// exactly two, edges used by another even count, edges used oddly or unbalanced}.
std::array<std::size_t, 3> edge_use(const std::vector<Tri>& tris) {
    using P = std::array<float, 3>;
    std::map<std::pair<P, P>, std::pair<int, int>> edges;  // {count, a->b minus b->a}
    for (const Tri& t : tris)
        for (int k = 0; k < 3; ++k) {
            const P a = t.v[static_cast<std::size_t>(k)], b = t.v[static_cast<std::size_t>((k + 1) % 3)];
            auto& e = a < b ? edges[{a, b}] : edges[{b, a}];
            ++e.first;
            e.second += a < b ? 1 : -1;
        }
    std::array<std::size_t, 3> out{};
    for (const auto& [edge, use] : edges) {
        if (use.second != 0 || use.first % 2 != 0) ++out[2];
        else if (use.first == 2) ++out[0];
        else ++out[1];
    }
    return out;
}

double remaining(const SimResult& r) {
    double v = 0;
    for (float h : r.field.heights) v += static_cast<double>(h) - r.field.bottom;
    return v * r.field.cell * r.field.cell;
}

TEST_CASE("pictures: the PNG's top view is the part's depth colour where cut, the top colour where not, white through") {
    const SimResult r = pocket_and_hole();
    std::ostringstream out;
    const TopViewFrame f = write_simulation_png(r, std::nullopt, {"p.ngc", "linuxcnc"}, out);
    const Decoded d = decode(out.str());
    CHECK(d.width == f.width);
    CHECK(d.height == f.height);
    // 40 x 30 mm fits 900 x 640 px at 640 / 30 px/mm.
    CHECK(f.scale == doctest::Approx(640.0 / 30));
    auto px = [&](double x, double y) { return d.at(f.left + (x - f.x0) * f.scale, f.top + (f.y1 - y) * f.scale); };
    CHECK(px(20, 15) == depth_colour(0.4));  // the pocket's floor, 4 of 10 mm down, flat: unshaded
    CHECK(px(2, 2) == depth_colour(0.0));    // the uncut corner
    CHECK(px(35, 25) == no_material_colour); // the hole through
    CHECK(depth_colour(0.4) != depth_colour(0.0));
    CHECK(depth_colour(1.0) == Rgb{22, 26, 84});
    // The same bytes again: deterministic.
    std::ostringstream again;
    write_simulation_png(r, std::nullopt, {"p.ngc", "linuxcnc"}, again);
    CHECK(again.str() == out.str());
}

TEST_CASE("pictures: the section follows the field, and the PNG draws it to scale under the top view") {
    const SimResult r = pocket_and_hole();
    const SectionLine line{{0, 15}, {40, 15}};
    const std::vector<SectionSample> samples = field_section(r.field, line);
    REQUIRE(samples.size() == 1601);  // every quarter cell
    // At Y15, 1 mm from the rows at Y14 and Y16, the tool's disc reaches sqrt(3^2 - 1) beyond
    // the rows' ends: the pocket spans X 10 - sqrt 8 to 30 + sqrt 8 there.
    const double lo = 10 - std::sqrt(8.0), hi = 30 + std::sqrt(8.0);
    int checked = 0;
    for (const SectionSample& s : samples) {
        const double x = s.distance;
        if (std::abs(x - lo) < 0.15 || std::abs(x - hi) < 0.15 || x > 39.95) continue;
        CHECK(s.inside);
        CHECK(s.stock);
        CHECK_MESSAGE(s.height == doctest::Approx(x > lo && x < hi ? -4.0 : 0.0), "x ", x);
        ++checked;
    }
    CHECK(checked > 1500);
    // Off the field: not inside.
    CHECK_FALSE(field_section(r.field, {{-5, 15}, {-1, 15}}).front().inside);

    std::ostringstream out;
    const TopViewFrame f = write_simulation_png(r, line, {"p.ngc", "linuxcnc"}, out);
    const Decoded d = decode(out.str());
    REQUIRE(f.section_scale > 0);
    CHECK(f.section_z_scale == doctest::Approx(f.section_scale));  // 10 mm at 21 px/mm: to scale
    auto sec = [&](double dist, double z) {
        return d.at(f.section_left + dist * f.section_scale, f.section_base - (z - r.field.bottom) * f.section_z_scale);
    };
    const Rgb material{150, 160, 176}, background{0xf4, 0xf4, 0xf4};
    CHECK(sec(20, -7) == material);     // below the pocket's floor
    CHECK(sec(20, -2) == background);   // cut away above it
    CHECK(sec(3, -2) == material);      // beside the pocket, under the uncut top
}

TEST_CASE("pictures: the STL of a hand-made field has the derived triangles, every edge twice, its volume") {
    // 4 x 4 cells of 1 mm, the top at 0 and the bottom at -5, the middle 2 x 2 cells at -2.
    SimResult r;
    r.kind = MachineKind::mill;
    HeightField& f = r.field;
    f.nx = f.ny = 4, f.cell = 1, f.x0 = 10, f.y0 = 20, f.top = 0, f.bottom = -5;
    f.heights.assign(16, 0.0f);
    f.lines.assign(16, 0);
    for (int j : {1, 2})
        for (int i : {1, 2}) f.heights[static_cast<std::size_t>(j * 4 + i)] = -2.0f;
    std::ostringstream out;
    const StlSummary s = write_simulation_stl(r, {}, out);
    // 16 columns x (2 top + 2 bottom) + 8 pocket walls x 2 + 16 outside walls x 2.
    CHECK(s.triangles == 112);
    CHECK(s.block == 1);
    const std::vector<Tri> tris = read_stl(out.str());
    CHECK(tris.size() == 112);
    const auto use = edge_use(tris);
    CHECK(use[0] > 0);
    CHECK(use[1] == 0);
    CHECK(use[2] == 0);
    CHECK(volume_and_area(tris).first == doctest::Approx(16 * 5 - 4 * 2).epsilon(1e-9));
}

TEST_CASE("pictures: the STL of a simulated part is closed and holds the simulation's remaining volume") {
    const SimResult r = pocket_and_hole();
    std::ostringstream out;
    const StlSummary s = write_simulation_stl(r, {}, out);
    CHECK(s.block == 1);  // 120,000 cells, within the budget
    const std::vector<Tri> tris = read_stl(out.str());
    CHECK(tris.size() == s.triangles);
    const auto use = edge_use(tris);
    CHECK(use[2] == 0);  // closed and consistently oriented
    MESSAGE("edges used twice ", use[0], ", by four (saddle corners) ", use[1]);
    const auto [volume, area] = volume_and_area(tris);
    // Each vertex is a float: within 2^-24 of its coordinates' size (at most 40 mm); the volume
    // moves by at most the area times that.
    const double bound = area * 40 * std::ldexp(1.0, -24) * 3;
    MESSAGE("STL volume ", volume, " simulated ", r.initial_volume - r.removed_volume, " bound ", bound);
    CHECK(std::abs(volume - remaining(r)) <= bound);
    CHECK(std::abs(remaining(r) - (r.initial_volume - r.removed_volume)) < 1e-6 * r.initial_volume);
    // Blocks of cells keep the volume too.
    std::ostringstream merged;
    const StlSummary m = write_simulation_stl(r, StlOptions{1000}, merged);
    CHECK(m.block == 11);  // 120,000 cells / 11^2 < 1000
    const std::vector<Tri> mt = read_stl(merged.str());
    CHECK(edge_use(mt)[2] == 0);
    CHECK(std::abs(volume_and_area(mt).first - remaining(r)) <= volume_and_area(mt).second * 40 * std::ldexp(1.0, -24) * 3);
    // Deterministic.
    std::ostringstream again;
    write_simulation_stl(r, {}, again);
    CHECK(again.str() == out.str());
}

// A bar turned by hand: D40 from Z-50 to 0, turned to radius 15 from Z-30, bored to radius 5
// from Z-10.
SimResult turned() {
    SimResult r;
    r.kind = MachineKind::lathe;
    LatheProfile& p = r.lathe;
    p.z0 = -50, p.dz = 0.5, p.nz = 100;
    for (int k = 0; k < p.nz; ++k) {
        p.outside.push_back(p.z(k) < -30 ? 20.0 : 15.0);
        p.bore.push_back(p.z(k) > -10 ? 5.0 : 0.0);
    }
    r.resolution = 0.5;
    r.cells = 100;
    return r;
}

TEST_CASE("pictures: a lathe's revolved STL has the derived triangles, every edge twice, the polygon's volume") {
    const SimResult r = turned();
    std::ostringstream out;
    const int n = 128;
    const StlSummary s = write_simulation_stl(r, {250'000, n, 4000}, out);
    // The foot's disc (n), the D40 band (2n), the shoulder's ring (2n), the D30 band (2n), the
    // bore's floor, a disc (n), the last band's outside and bore (2n + 2n), the face's ring (2n).
    CHECK(s.triangles == 14 * n);
    const std::vector<Tri> tris = read_stl(out.str());
    const auto use = edge_use(tris);
    CHECK(use[1] == 0);
    CHECK(use[2] == 0);
    double simulated = 0;
    for (int k = 0; k < r.lathe.nz; ++k)
        simulated += pi_ * (std::pow(r.lathe.outside[k], 2) - std::pow(r.lathe.bore[k], 2)) * r.lathe.dz;
    // Vertices on the circle: each ring's polygon has n/2 sin(2 pi / n) r^2 of its pi r^2.
    const double polygon = simulated * n * std::sin(2 * pi_ / n) / (2 * pi_);
    const auto [volume, area] = volume_and_area(tris);
    CHECK(std::abs(volume - polygon) <= area * 50 * std::ldexp(1.0, -24) * 3);
    // Bands merged (2 samples a band): the volume kept.
    std::ostringstream merged;
    const StlSummary m = write_simulation_stl(r, {250'000, n, 50}, merged);
    CHECK(m.block == 2);
    const std::vector<Tri> mt = read_stl(merged.str());
    CHECK(edge_use(mt)[2] == 0);
    CHECK(std::abs(volume_and_area(mt).first - polygon) <= volume_and_area(mt).second * 50 * std::ldexp(1.0, -24) * 3);
}

TEST_CASE("pictures: a lathe's PNG is its half-section: material between bore and outside, air where turned") {
    const SimResult r = turned();
    std::ostringstream out;
    const TopViewFrame f = write_simulation_png(r, std::nullopt, {"s.nc", "fanuc-lathe"}, out);
    const Decoded d = decode(out.str());
    CHECK(d.width == f.width);
    CHECK(d.height == f.height);
    auto px = [&](double z, double rad) { return d.at(f.left + (z - f.x0) * f.scale, f.top + (f.y1 - rad) * f.scale); };
    const Rgb material{150, 160, 176}, background{0xf4, 0xf4, 0xf4};
    CHECK(px(-40, 10) == material);
    CHECK(px(-20, 10) == material);
    CHECK(px(-20, 17.5) == background);  // turned from 20 to 15
    CHECK(px(-5, 2.5) == background);    // the bore
    CHECK(px(-5, 10) == material);
    std::ostringstream bad;
    CHECK_THROWS_AS(write_simulation_png(r, SectionLine{{0, 0}, {1, 1}}, {"s.nc", "fanuc-lathe"}, bad), SimInputError);
}

// turned() with a face groove's rings of air in its last 10 mm: from radius 8 to 11 (a second
// ring from 12 to 13 in the last 2 mm), its 2 mm below ringed wider, 7.5 to 11.
SimResult ringed() {
    SimResult r = turned();
    LatheProfile& p = r.lathe;
    p.gaps.resize(static_cast<std::size_t>(p.nz));
    for (int k = 0; k < p.nz; ++k) {
        const double z = p.z(k);
        auto& g = p.gaps[static_cast<std::size_t>(k)];
        if (z > -10) g.push_back({z > -2 ? 7.5 : 8.0, 11.0, 1});
        if (z > -2) g.push_back({12.0, 13.0, 2});
    }
    return r;
}

TEST_CASE("pictures: a lathe part's rings of air (face grooves) are air in the PNG and walls of the closed STL") {
    const SimResult r = ringed();
    const int n = 64;
    double simulated = 0;
    for (int k = 0; k < r.lathe.nz; ++k)
        simulated += lathe_material_area(r.lathe.outside[static_cast<std::size_t>(k)], r.lathe.bore[static_cast<std::size_t>(k)],
                                         r.lathe.gaps_at(k)) *
                     r.lathe.dz;
    const double polygon = simulated * n * std::sin(2 * pi_ / n) / (2 * pi_);
    for (const std::size_t bands : {std::size_t{4000}, std::size_t{50}, std::size_t{30}}) {
        INFO("bands " << bands);
        std::ostringstream out;
        write_simulation_stl(r, {250'000, n, bands}, out);
        const std::vector<Tri> tris = read_stl(out.str());
        const auto use = edge_use(tris);
        CHECK(use[1] == 0);
        CHECK(use[2] == 0);
        const auto [volume, area] = volume_and_area(tris);
        CHECK(std::abs(volume - polygon) <= area * 50 * std::ldexp(1.0, -24) * 3 + 1e-6 * polygon);
    }
    // The rings themselves: more triangles than without them.
    std::ostringstream plain, rings;
    CHECK(write_simulation_stl(r, {250'000, n, 4000}, rings).triangles > write_simulation_stl(turned(), {250'000, n, 4000}, plain).triangles);
    std::ostringstream png;
    const TopViewFrame f = write_simulation_png(r, std::nullopt, {"s.nc", "fanuc-lathe"}, png);
    const Decoded d = decode(png.str());
    auto px = [&](double z, double rad) { return d.at(f.left + (z - f.x0) * f.scale, f.top + (f.y1 - rad) * f.scale); };
    const Rgb material{150, 160, 176}, background{0xf4, 0xf4, 0xf4};
    CHECK(px(-5, 9.5) == background);   // the ring
    CHECK(px(-5, 12.5) == material);    // between the rings where the second is not
    CHECK(px(-1, 12.5) == background);  // the second ring
    CHECK(px(-5, 13.5) == material);
    CHECK(px(-15, 9.5) == material);    // below the groove
}

// Replays a history up to `line` as the page does: each coarse cell the lowest of its initial
// value and its changes at lines up to `line`.
std::vector<float> replay(const SimHistory& h, int line) {
    std::vector<float> s = h.initial;
    for (const SimHistory::Event& e : h.events)
        if (e.line <= line) s[static_cast<std::size_t>(e.cell)] = std::min(s[static_cast<std::size_t>(e.cell)], e.value);
    return s;
}

TEST_CASE("pictures: the page's history replays to the final part, shows less cut early, and keeps its budget") {
    // The history is made from the part before the first move (a new Simulator's result).
    const Machine m = load_machine("linuxcnc");
    SimStock box;
    box.kind = SimStock::Kind::box;
    box.min = {0, 0, -10};
    box.max = {40, 30, 0};
    SimOptions o;
    o.resolution = 0.1;
    for (std::size_t budget : {SimHistory::default_event_budget, std::size_t{64}}) {
        CAPTURE(budget);
        Simulator sim(m, box, {{1, flat(6)}}, o);
        SimHistory h(sim.result(), budget);
        CHECK(h.factor == 2);  // 400 x 300 cells: 200 x 150 coarse cells
        CHECK(h.nx == 200);
        CHECK(h.ny == 150);
        sim.observe(&h);
        int line = 10;
        for (double y = 10; y <= 20 + 1e-9; y += 2) sim.step(feed({10, y, -4}, {30, y, -4}, line++));
        sim.step(feed({35, 25, 1}, {35, 25, -11}, 100));
        sim.finish({});
        const SimResult r = sim.take();
        h.finish(r);
        CHECK(h.events.size() <= budget + static_cast<std::size_t>(h.nx * h.ny));
        if (budget == 64) CHECK(h.thinned > 0);
        // Each coarse cell: the lowest of its four cells.
        std::vector<float> want(static_cast<std::size_t>(h.nx * h.ny), 1e9f);
        for (int j = 0; j < r.field.ny; ++j)
            for (int i = 0; i < r.field.nx; ++i) {
                float& c = want[static_cast<std::size_t>(j / 2 * h.nx + i / 2)];
                c = std::min(c, r.field.heights[static_cast<std::size_t>(j * r.field.nx + i)]);
            }
        CHECK(h.final == want);
        CHECK(replay(h, 1000) == want);
        auto cut = [&](const std::vector<float>& s) {
            int n = 0;
            for (std::size_t k = 0; k < s.size(); ++k) n += s[k] < h.initial[k];
            return n;
        };
        const int early = cut(replay(h, 10)), late = cut(replay(h, 1000));
        CHECK(early > 0);
        CHECK(early < late);
        CHECK(cut(replay(h, 9)) == 0);
    }
}

TEST_CASE("pictures: a lathe's history replays to its turned profile, band by band") {
    const Machine m = load_machine("linuxcnc-lathe");
    SimStock bar;
    bar.kind = SimStock::Kind::bar;
    bar.bar_diameter = 40;
    bar.bar_length = 100;
    ToolShape tip;
    tip.form = ToolForm::turning;
    SimOptions o;
    o.resolution = 0.01;  // 10,000 samples: bands of 10
    Simulator sim(m, bar, {{1, tip}}, o);
    SimHistory h(sim.result());
    CHECK(h.factor == 10);
    CHECK(h.nx == 1000);
    sim.observe(&h);
    Step face = feed({22, 0, -1}, {0, 0, -1}, 6), turn = feed({15, 0, 2}, {15, 0, -50}, 9);
    sim.step(face);
    sim.step(turn);
    sim.finish({});
    const SimResult r = sim.take();
    h.finish(r);
    const std::size_t n = static_cast<std::size_t>(h.nx);
    std::vector<float> want(2 * n);
    for (std::size_t c = 0; c < n; ++c) {
        float out = 1e9f, bore = 0;
        for (std::size_t k = 10 * c; k < 10 * c + 10; ++k) {
            out = std::min(out, static_cast<float>(r.lathe.outside[k]));
            bore = std::max(bore, static_cast<float>(r.lathe.bore[k]));
        }
        want[c] = out, want[n + c] = bore;
    }
    CHECK(h.final == want);
    // Replayed up to line 6 only the face is cut: the bands from Z-50 to -1 still hold radius 20.
    std::vector<float> s = h.initial;
    for (const SimHistory::Event& e : h.events)
        if (e.line <= 6) s[static_cast<std::size_t>(e.cell)] = std::min(s[static_cast<std::size_t>(e.cell)], e.value);
    CHECK(s[700] == 20.0f);   // Z -30: not turned yet
    CHECK(s[995] == 0.0f);    // Z -0.5: faced to the axis
    CHECK(h.final[700] == 15.0f);
}

TEST_CASE("camgen simulate --png --stl --plot: written after the run; a refused run writes nothing and leaves files") {
    const std::filesystem::path dir = test::scratch("sim-pictures");
    const std::string job = CAMGEN_SOURCE_DIR "/samples/pocket.json";
    const std::string nc = (dir / "pocket.ngc").string();
    {
        const test::Run posted = test::run({job, "--machine", "linuxcnc", "-o", nc});
        REQUIRE_MESSAGE(posted.code == 0, posted.err);
    }
    const std::string png = (dir / "p.png").string(), stl = (dir / "p.stl").string(), page = (dir / "p.html").string();
    const std::vector<std::string> base{"simulate", nc, "--machine", "linuxcnc", "--job", job, "--stock-box", "-10,-10,-12,110,80,0",
                                        "--resolution", "0.5"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        return test::run(a);
    };
    // Refused before anything is written: a section of three numbers, a section without a
    // picture, a page that is not .html, a picture over the job.
    std::ofstream(png) << "old";
    for (const auto& extra : std::vector<std::vector<std::string>>{{"--png", png, "--section", "1,2,3"},
                                                                   {"--stl", stl, "--section", "0,0,1,1"},
                                                                   {"--png", png, "--plot", (dir / "p.txt").string()},
                                                                   {"--png", png, "--stl", job}}) {
        const test::Run r = with(extra);
        CAPTURE(r.err);
        CHECK(r.code == 2);
        CHECK(test::read_file(png) == "old");
        CHECK_FALSE(std::filesystem::exists(stl));
    }
    const test::Run ok = with({"--png", png, "--section", "-10,30,110,30", "--stl", stl, "--plot", page});
    REQUIRE_MESSAGE(ok.code == 0, ok.err);
    CHECK(ok.out.find("stl: ") != std::string::npos);
    CHECK(test::read_file(png).compare(0, 4, "\x89PNG") == 0);
    CHECK(read_stl(test::read_file(stl)).size() > 1000);
    const std::string html = test::read_file(page);
    CHECK(html.find("id=\"camgen-sim\"") != std::string::npos);
    CHECK(html.find("getContext(\"webgl\"") != std::string::npos);
    CHECK(html.find("http") == std::string::npos);  // nothing loaded from the network
    // A lathe takes no section.
    const test::Run lathe = test::run({"simulate", nc, "--machine", "fanuc-lathe", "--job", job, "--bar", "40,80",
                                       "--png", png, "--section", "0,0,1,1"});
    CHECK(lathe.code == 2);
}

}  // namespace test_sim_pictures
