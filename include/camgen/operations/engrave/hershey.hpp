#pragma once
// Hershey single-stroke fonts in the .jhf form Debian's hershey-fonts-data installs
// (/usr/share/hershey-fonts/*.jhf): one glyph a record, the characters from 32 (space) on in
// file order. A record: a 5-character glyph number, a 3-character vertex count, then that many
// pairs of characters, each coordinate the character's code less 'R' (Y grows downwards); the
// first pair is the glyph's left and right bound, a pair " R" lifts the pen. A record longer
// than a line continues on the next (the original distribution wraps at 72 characters).
// The reading is strict and bounded: anything else is an error naming the file, the line and
// what is wrong, never a crash.
#include <algorithm>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace camgen {

// A font file that cannot be read or is not a font.
class FontError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A glyph in font units (X right, Y down, as in the file).
struct HersheyPoint {
    int x = 0;
    int y = 0;
    friend bool operator==(const HersheyPoint&, const HersheyPoint&) = default;
};

struct HersheyGlyph {
    int number = 0;  // the Hershey glyph number of the record
    int left = 0;    // the bounds the next glyph starts after: its advance is right - left
    int right = 0;
    std::vector<std::vector<HersheyPoint>> strokes;  // each a pen-down polyline
};

struct HersheyFont {
    std::string name;  // "rowmans"
    std::string file;  // where it was read
    std::vector<HersheyGlyph> glyphs;  // glyph k is character 32 + k
    // The last character a font's text may use: printable ASCII (a font's 96th record, at
    // U+007F, is DEL's place: a control character, never engraved).
    static constexpr char32_t last_character = 0x7E;
    // The glyph of character code `c`, or none where the font has none.
    const HersheyGlyph* glyph(char32_t c) const {
        if (c < 32 || c > last_character || c - 32 >= glyphs.size()) return nullptr;
        return &glyphs[c - 32];
    }
    // The last character it has a glyph for.
    char32_t last() const { return std::min<char32_t>(last_character, static_cast<char32_t>(32 + glyphs.size() - 1)); }
    // The cap height's top and the baseline in font units (Y down): the extent of the "H"
    // glyph's points where it has any, else Hershey's usual -12 and 9.
    int cap_top = -12;
    int baseline = 9;
};

// At most this many bytes in a font file and this many glyphs: larger is no Hershey font.
inline constexpr std::size_t hershey_max_bytes = 4u << 20;
inline constexpr std::size_t hershey_max_glyphs = 10000;

// Reads a font from the text of a .jhf file; `file` names it in messages. Throws FontError
// ("rowmans.jhf line 12: ...").
HersheyFont parse_hershey(std::string_view text, const std::string& file, const std::string& name);

// The folder the fonts are read from: $CAMGEN_FONTS where set and not empty, else
// /usr/share/hershey-fonts (Debian's hershey-fonts-data).
std::string hershey_font_directory();

// Reads font `name` (letters, digits, '_' and '-' only: "rowmans") from `directory`
// (<directory>/<name>.jhf). Throws FontError when the name is not a font name, the file is
// missing (naming the folder, the CAMGEN_FONTS setting and the Debian package), too large, or
// not a font.
HersheyFont load_hershey_font(const std::string& name, const std::string& directory);

}  // namespace camgen
