// The DXF reader's streaming and memory (issue 28's speed target): the pieces handed to a sink
// as read_file keeps them, origins that view the drawing's own text (valid while a copy of the
// Drawing lives), pieces held until a late layer table, paths moved into chains, a vertex count
// that lies, and NUL bytes wherever they stand. The speed and the peak memory themselves are
// measured by bench/run dxf (bench/dxf.sh), not here: a test of time or of a process's memory
// would be at the mercy of the machine.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "camgen/dxf/dxf.hpp"

namespace test_dxf_stream {

using namespace camgen;

std::string drawing(const std::string& name) { return std::string(CAMGEN_SOURCE_DIR "/tests/dxf/") + name; }

void same_piece(const dxf::Piece& a, const dxf::Piece& b) {
    CHECK(a.kind == b.kind);
    CHECK(a.origin.type == b.origin.type);
    CHECK(a.origin.handle == b.origin.handle);
    CHECK(a.origin.layer == b.origin.layer);
    CHECK(a.origin.linetype == b.origin.linetype);
    CHECK(a.origin.colour == b.origin.colour);
    CHECK(a.origin.line == b.origin.line);
    CHECK(std::vector<std::string_view>(a.origin.blocks.begin(), a.origin.blocks.end()) ==
          std::vector<std::string_view>(b.origin.blocks.begin(), b.origin.blocks.end()));
    CHECK(a.centre == b.centre);
    CHECK(a.radius == b.radius);
    CHECK(a.closed == b.closed);
    CHECK(a.path.start == b.path.start);
    CHECK(a.path.segments == b.path.segments);
}

TEST_CASE("dxf stream: read_file hands each piece to a sink, in the order and with the origins read_file keeps") {
    for (const char* name : {"plate.dxf", "blocks.dxf", "entities.dxf", "ocs.dxf", "freecad.dxf"}) {
        INFO(name);
        const dxf::Drawing kept = dxf::read_file(drawing(name));
        std::vector<dxf::Piece> handed;
        const dxf::Drawing d = dxf::read_file(drawing(name), [&](dxf::Piece&& p) { handed.push_back(std::move(p)); });
        CHECK(d.pieces.empty());
        REQUIRE(handed.size() == kept.pieces.size());
        for (std::size_t i = 0; i < handed.size(); ++i) same_piece(handed[i], kept.pieces[i]);
        CHECK(d.insunits == kept.insunits);
        CHECK(d.notes == kept.notes);
        REQUIRE(d.layers.size() == kept.layers.size());
        for (std::size_t i = 0; i < d.layers.size(); ++i) CHECK(d.layers[i].name == kept.layers[i].name);
    }
}

TEST_CASE("dxf stream: an origin's text lives with the drawing, shared by its copies") {
    std::optional<dxf::Drawing> first = dxf::read_file(drawing("blocks.dxf"));
    const dxf::Drawing copy = *first;
    first.reset();
    const dxf::Drawing again = dxf::read_file(drawing("blocks.dxf"));
    REQUIRE(!copy.pieces.empty());
    REQUIRE(copy.pieces.size() == again.pieces.size());
    for (std::size_t i = 0; i < copy.pieces.size(); ++i) {
        const dxf::Piece& p = copy.pieces[i];
        CHECK(p.origin.layer == "HOLES");
        REQUIRE(!p.origin.blocks.empty());
        CHECK(p.origin.blocks.back() == "HOLE");
        CHECK(!p.origin.handle.empty());
        CHECK(dxf::describe(p.origin) == dxf::describe(again.pieces[i].origin));
    }
    // A piece is views and numbers: four strings (and a vector of them) per piece would make it
    // more than this, and cost heap allocations besides.
    CHECK(sizeof(dxf::Piece) <= 192);
}

TEST_CASE("dxf stream: pieces before a late layer table are held until it is read, then resolved by it") {
    const std::string text = "0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n5\nC1\n8\nH\n10\n1\n20\n2\n40\n3\n0\nENDSEC\n"
                             "0\nSECTION\n2\nTABLES\n0\nTABLE\n2\nLAYER\n0\nLAYER\n2\nH\n62\n3\n6\nDASHED\n0\nENDTAB\n0\nENDSEC\n0\nEOF\n";
    std::vector<dxf::Piece> handed;
    const dxf::Drawing d = dxf::read_text(text, "t.dxf", [&](dxf::Piece&& p) { handed.push_back(std::move(p)); });
    REQUIRE(handed.size() == 1);
    CHECK(handed[0].origin.colour == 3);
    CHECK(handed[0].origin.linetype == "DASHED");
    CHECK(handed[0].origin.handle == "C1");
    REQUIRE(d.layers.size() == 1);
    CHECK(d.layers[0].name == "H");
}

TEST_CASE("dxf stream: chain_taking gives chain's chains and moves the paths out of the pieces") {
    const dxf::Drawing d = dxf::read_file(drawing("plate.dxf"));
    const dxf::ChainResult want = dxf::chain(dxf::select(d, {}, "a profile"), 0.01, "plate.dxf");
    std::vector<dxf::Piece> own = d.pieces;
    std::vector<dxf::Piece*> take;
    for (dxf::Piece& p : own) take.push_back(&p);
    const dxf::ChainResult got = dxf::chain_taking(take, 0.01, "plate.dxf");
    CHECK(got.notes == want.notes);
    REQUIRE(got.chains.size() == want.chains.size());
    for (std::size_t i = 0; i < got.chains.size(); ++i) {
        CHECK(got.chains[i].closed == want.chains[i].closed);
        CHECK(got.chains[i].profile.start == want.chains[i].profile.start);
        CHECK(got.chains[i].profile.segments == want.chains[i].profile.segments);
        REQUIRE(got.chains[i].pieces.size() == want.chains[i].pieces.size());
        for (std::size_t k = 0; k < got.chains[i].pieces.size(); ++k)
            CHECK(got.chains[i].pieces[k]->origin.line == want.chains[i].pieces[k]->origin.line);
    }
    for (const dxf::Piece& p : own)
        if (p.kind == dxf::Piece::Kind::path) CHECK(p.path.segments.empty());
}

std::string error_of(const std::string& text) {
    try {
        dxf::read_text(text, "t.dxf");
    } catch (const dxf::Error& e) {
        return e.what();
    }
    return "";
}

TEST_CASE("dxf stream: an LWPOLYLINE read vertex by vertex") {
    // A vertex count (90) far beyond what the file could hold reserves no more than the text.
    const std::string lie = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n5\nP1\n8\nCUT\n90\n2000000000\n70\n1\n"
                            "10\n0\n20\n0\n10\n10\n20\n0\n42\n1\n10\n10\n20\n10\n10\n0\n20\n10\n0\nENDSEC\n0\nEOF\n";
    const dxf::Drawing d = dxf::read_text(lie, "t.dxf");
    REQUIRE(d.pieces.size() == 1);
    CHECK(d.pieces[0].closed);
    REQUIRE(d.pieces[0].path.segments.size() == 4);
    CHECK(d.pieces[0].path.segments[1].centre == Vec2{10, 5});
    CHECK(d.pieces[0].path.segments.capacity() < 100);
    // A fault in a vertex names the handle and layer even when they stand after the vertices.
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n10\n0\n20\nx1\n10\n1\n20\n1\n5\nP2\n8\nCUT\n0\nENDSEC\n0\nEOF\n") ==
          "t.dxf line 9: LWPOLYLINE (handle P2, layer CUT): group code 20 needs a number, got \"x1\"");
    CHECK(error_of("0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n5\nP3\n20\n1\n10\n1\n0\nENDSEC\n0\nEOF\n") ==
          "t.dxf line 9: LWPOLYLINE (handle P3, layer 0): a vertex's Y (20) before its X (10)");
    // Repeated vertices dropped with a note; a polyline of nothing but repeats dropped.
    const dxf::Drawing r = dxf::read_text("0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n5\nP4\n10\n0\n20\n0\n10\n0\n20\n0\n10\n5\n20\n0\n"
                                          "0\nLWPOLYLINE\n5\nP5\n10\n1\n20\n1\n10\n1\n20\n1\n0\nENDSEC\n0\nEOF\n",
                                          "t.dxf");
    REQUIRE(r.pieces.size() == 1);
    CHECK(r.pieces[0].path.segments.size() == 1);
    REQUIRE(r.notes.size() == 3);
    CHECK(r.notes[0] == "t.dxf line 5: LWPOLYLINE (handle P4, layer 0): 1 zero-length segment dropped");
    CHECK(r.notes[1] == "t.dxf line 21: LWPOLYLINE (handle P5, layer 0): 1 zero-length segment dropped");
    CHECK(r.notes[2] == "t.dxf line 21: LWPOLYLINE (handle P5, layer 0): a polyline of no length dropped");
}

TEST_CASE("dxf stream: a NUL byte anywhere makes the file a binary one, whatever else is wrong with it") {
    const std::string binary = "t.dxf: a binary file, not an ASCII DXF drawing";
    const std::string good = "0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n8\nH\n10\n1\n20\n1\n40\n1\n0\nENDSEC\n0\nEOF\n";
    CHECK(error_of(good).empty());
    CHECK(error_of(good.substr(0, 10) + std::string(1, '\0') + good.substr(10)) == binary);
    CHECK(error_of(good + std::string("junk\0", 5)) == binary);                               // after EOF
    CHECK(error_of("0\nSECTION\n2\nENTITIES\nx\n" + std::string("\0", 1) + "\n") == binary);  // a fault before it
}

}  // namespace test_dxf_stream
