// Hershey .jhf fonts (hershey.hpp): a strict, bounded reader.
#include "camgen/operations/engrave/hershey.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include <fmt/format.h>

namespace camgen {

namespace {

// A field of digits with leading spaces ("  699", " 12"), or none.
std::optional<int> hershey_number(std::string_view field) {
    std::size_t i = 0;
    while (i < field.size() && field[i] == ' ') ++i;
    if (i == field.size()) return std::nullopt;
    int value = 0;
    for (; i < field.size(); ++i) {
        if (field[i] < '0' || field[i] > '9') return std::nullopt;
        value = value * 10 + (field[i] - '0');
    }
    return value;
}

// A character shown in a message: itself where printable, else its code.
std::string hershey_shown(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 33 && u < 127) return fmt::format("'{}'", c);
    return fmt::format("byte {}", static_cast<int>(u));
}

}  // namespace

HersheyFont parse_hershey(std::string_view text, const std::string& file, const std::string& name) {
    if (text.size() > hershey_max_bytes)
        throw FontError(fmt::format("{}: {} bytes, more than a font's {}: not a Hershey font", file, text.size(), hershey_max_bytes));
    HersheyFont font;
    font.name = name;
    font.file = file;
    // The lines, without their line ends ("\n" or "\r\n").
    std::vector<std::string_view> lines;
    for (std::size_t at = 0; at < text.size();) {
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(at, end - at);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        lines.push_back(line);
        at = end + 1;
    }
    auto fail = [&](std::size_t line, const std::string& what) -> FontError {
        return FontError(fmt::format("{} line {}: {}", file, line + 1, what));
    };
    for (std::size_t k = 0; k < lines.size();) {
        const std::size_t first = k;
        std::string_view line = lines[k];
        if (line.empty()) {
            // A last empty line is the file's final line end; an empty line elsewhere is no glyph.
            if (k + 1 == lines.size() || std::all_of(lines.begin() + static_cast<std::ptrdiff_t>(k), lines.end(),
                                                     [](std::string_view l) { return l.empty(); }))
                break;
            throw fail(k, "an empty line where a glyph record should be");
        }
        if (line.size() < 8) throw fail(k, fmt::format("a glyph record needs 8 characters of number and vertex count, this line has {}", line.size()));
        const std::optional<int> number = hershey_number(line.substr(0, 5));
        if (!number) throw fail(k, fmt::format("the glyph number (columns 1 to 5) is \"{}\", not a number", line.substr(0, 5)));
        const std::optional<int> count = hershey_number(line.substr(5, 3));
        if (!count) throw fail(k, fmt::format("the vertex count (columns 6 to 8) is \"{}\", not a number", line.substr(5, 3)));
        if (*count < 1) throw fail(k, "the vertex count is 0: a glyph has at least its bounds");
        if (font.glyphs.size() >= hershey_max_glyphs) throw fail(k, fmt::format("more than {} glyphs: not a Hershey font", hershey_max_glyphs));
        // The record's pairs, continued on the next lines where the line is shorter.
        const std::size_t need = 2 * static_cast<std::size_t>(*count);
        std::string pairs(line.substr(8));
        while (pairs.size() < need) {
            if (++k >= lines.size() || lines[k].empty())
                throw fail(first, fmt::format("glyph {} has {} vertices ({} characters), but its record ends after {} characters",
                                              *number, *count, need, pairs.size()));
            pairs += lines[k];
        }
        if (pairs.size() > need)
            throw fail(k, fmt::format("glyph {} has {} vertices ({} characters), but its record has {} characters", *number,
                                      *count, need, pairs.size()));
        HersheyGlyph g;
        g.number = *number;
        for (std::size_t i = 0; i < need; ++i)
            if (pairs[i] < ' ' || pairs[i] > '~')
                throw fail(k, fmt::format("glyph {}: {} at vertex {} is no coordinate (characters ' ' to '~')", *number,
                                          hershey_shown(pairs[i]), i / 2));
        g.left = pairs[0] - 'R';
        g.right = pairs[1] - 'R';
        if (g.left > g.right)
            throw fail(first, fmt::format("glyph {}: its left bound ({}) is right of its right bound ({})", *number, g.left, g.right));
        std::vector<HersheyPoint> stroke;
        for (std::size_t i = 2; i < need; i += 2) {
            if (pairs[i] == ' ' && pairs[i + 1] == 'R') {
                if (!stroke.empty()) g.strokes.push_back(std::move(stroke));
                stroke.clear();
                continue;
            }
            if (pairs[i] == ' ' || pairs[i + 1] == ' ')
                throw fail(k, fmt::format("glyph {}: vertex {} is \"{}{}\": a space only lifts the pen, as \" R\"", *number, i / 2,
                                          pairs[i], pairs[i + 1]));
            stroke.push_back({pairs[i] - 'R', pairs[i + 1] - 'R'});
        }
        if (!stroke.empty()) g.strokes.push_back(std::move(stroke));
        font.glyphs.push_back(std::move(g));
        ++k;
    }
    if (font.glyphs.empty()) throw FontError(fmt::format("{}: no glyphs: not a Hershey font", file));
    if (const HersheyGlyph* h = font.glyph('H'); h && !h->strokes.empty()) {
        int top = std::numeric_limits<int>::max(), bottom = std::numeric_limits<int>::min();
        for (const auto& s : h->strokes)
            for (const HersheyPoint& p : s) top = std::min(top, p.y), bottom = std::max(bottom, p.y);
        if (bottom > top) font.cap_top = top, font.baseline = bottom;
    }
    return font;
}

std::string hershey_font_directory() {
    const char* env = std::getenv("CAMGEN_FONTS");
    if (env && *env) return env;
    return "/usr/share/hershey-fonts";
}

HersheyFont load_hershey_font(const std::string& name, const std::string& directory) {
    const bool valid = !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    });
    if (!valid)
        throw FontError(fmt::format("\"{}\" is not a font name (letters, digits, '_' and '-', as \"rowmans\" for {}/rowmans.jhf)",
                                    name, directory));
    const std::filesystem::path path = std::filesystem::path(directory) / (name + ".jhf");
    std::error_code ec;
    const bool regular = std::filesystem::is_regular_file(path, ec);
    if (!regular) {
        std::string known;
        std::vector<std::string> names;
        if (std::filesystem::is_directory(directory, ec)) {
            for (const auto& e : std::filesystem::directory_iterator(directory, ec))
                if (e.path().extension() == ".jhf") names.push_back(e.path().stem().string());
            std::sort(names.begin(), names.end());
        }
        for (std::size_t i = 0; i < names.size() && i < 40; ++i) known += (i ? ", " : "") + names[i];
        throw FontError(fmt::format("font \"{}\" not found: no {} ({}; the fonts are Debian's package hershey-fonts-data, "
                                    "apt-get install hershey-fonts-data; CAMGEN_FONTS names another folder){}",
                                    name, path.string(),
                                    std::getenv("CAMGEN_FONTS") && *std::getenv("CAMGEN_FONTS") ? "the folder CAMGEN_FONTS names"
                                                                                                : "the default folder",
                                    names.empty() ? std::string(", and the folder holds no fonts") : "; the folder holds " + known));
    }
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw FontError(fmt::format("{}: cannot be read ({})", path.string(), ec.message()));
    if (size > hershey_max_bytes)
        throw FontError(fmt::format("{}: {} bytes, more than a font's {}: not a Hershey font", path.string(), size, hershey_max_bytes));
    std::ifstream in(path, std::ios::binary);
    std::string text(static_cast<std::size_t>(size), '\0');
    if (!in || !in.read(text.data(), static_cast<std::streamsize>(size)))
        throw FontError(fmt::format("{}: cannot be read", path.string()));
    return parse_hershey(text, path.string(), name);
}

}  // namespace camgen
