#include "camgen/common/file_kind.hpp"

#include <filesystem>
#include <algorithm>
#include <cctype>
#include <vector>

#include <fmt/format.h>

namespace camgen {

namespace {

// Enough of a file to say what it is.
constexpr std::size_t head_size = std::size_t{1} << 16;

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

char upper(char c) { return static_cast<char>(std::toupper(static_cast<unsigned char>(c))); }

bool starts_with_nocase(std::string_view text, std::string_view prefix) {
    if (text.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i)
        if (upper(text[i]) != upper(prefix[i])) return false;
    return true;
}

bool contains_nocase(std::string_view text, std::string_view what) {
    return std::search(text.begin(), text.end(), what.begin(), what.end(),
                       [](char a, char b) { return upper(a) == upper(b); }) != text.end();
}

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

std::string_view trim(std::string_view s) {
    while (!s.empty() && blank(s.front())) s.remove_prefix(1);
    while (!s.empty() && blank(s.back())) s.remove_suffix(1);
    return s;
}

bool digit(char c) { return c >= '0' && c <= '9'; }

// The first `n` lines that are not blank, trimmed.
std::vector<std::string_view> first_lines(std::string_view text, std::size_t n) {
    std::vector<std::string_view> lines;
    while (!text.empty() && lines.size() < n) {
        const std::size_t nl = text.find('\n');
        const std::string_view line = trim(text.substr(0, nl));
        if (!line.empty()) lines.push_back(line);
        if (nl == std::string_view::npos) break;
        text.remove_prefix(nl + 1);
    }
    return lines;
}

// A block of G-code: an optional block delete and block number, then an address letter with
// a number ("N10 G0 X5", "G90", "T1 M6", "X10 Y5"); a Fanuc program number (O1000); a program
// start or end (%); nccad's empty header lines ("_").
bool looks_like_block(std::string_view line) {
    if (line == "%" || line == "_") return true;
    if (line.size() >= 2 && upper(line[0]) == 'O' && digit(line[1])) return true;
    if (!line.empty() && line[0] == '/') line.remove_prefix(1);
    if (line.size() >= 2 && upper(line[0]) == 'N' && digit(line[1])) {
        std::size_t i = 1;
        while (i < line.size() && digit(line[i])) ++i;
        line = trim(line.substr(i));
        if (line.empty()) return true;
    }
    if (line.size() < 2) return false;
    const char letter = upper(line[0]);
    std::size_t i = 1;
    if (line[i] == '-' || line[i] == '+') ++i;
    return std::string_view("GMTXYZFSIJKRDHP").find(letter) != std::string_view::npos && i < line.size() &&
           (digit(line[i]) || line[i] == '.');
}

// A G or M word anywhere in the line ("G0", "M30", "g01").
bool has_g_or_m_word(std::string_view line) {
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const char c = upper(line[i]);
        if ((c == 'G' || c == 'M') && digit(line[i + 1]) && (i == 0 || !std::isalpha(static_cast<unsigned char>(line[i - 1]))))
            return true;
    }
    return false;
}

bool comment_line(std::string_view line) { return !line.empty() && (line[0] == '(' || line[0] == ';'); }

// A Heidenhain conversational program: "0 BEGIN PGM NAME MM".
bool heidenhain_line(std::string_view line) {
    std::size_t i = 0;
    while (i < line.size() && digit(line[i])) ++i;
    return starts_with_nocase(trim(line.substr(i)), "BEGIN PGM");
}

// G-code: it starts with a block or a comment, most of its first lines are blocks (a
// Sinumerik MCALL CYCLE81(...) or DIAMON is not, but few lines are like it), and one of them
// has a G or M word.
bool nc_program(std::string_view head) {
    const std::vector<std::string_view> lines = first_lines(head, 40);
    if (lines.empty()) return false;
    if (heidenhain_line(lines.front())) return true;
    if (!looks_like_block(lines.front()) && !comment_line(lines.front())) return false;
    int blocks = 0, others = 0;
    bool g_or_m = false;
    for (std::string_view line : lines) {
        if (comment_line(line)) continue;
        if (looks_like_block(line)) ++blocks;
        else ++others;
        g_or_m = g_or_m || has_g_or_m_word(line);
    }
    return blocks > 0 && blocks >= 2 * others && g_or_m;
}

// An ASCII DXF: group code 0 and SECTION first (after any 999 comments).
bool ascii_dxf(std::string_view head) {
    const std::vector<std::string_view> lines = first_lines(head, 12);
    std::size_t i = 0;
    while (i + 1 < lines.size() && lines[i] == "999") i += 2;
    return i + 1 < lines.size() && lines[i] == "0" && starts_with_nocase(lines[i + 1], "SECTION");
}

bool binary_text(std::string_view head) {
    if (head.find('\0') != std::string_view::npos) return true;
    const std::string_view sample = head.substr(0, 4096);
    std::size_t control = 0;
    for (char ch : sample) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 && !blank(ch) && c != 0x1b) ++control;
    }
    return !sample.empty() && control * 10 > sample.size();
}

}  // namespace

FileKind file_kind(std::string_view text, bool cut) {
    std::string_view head = text.substr(0, head_size);
    if (starts_with(head, "\xFF\xFE") || starts_with(head, "\xFE\xFF")) return FileKind::utf16;
    if (starts_with(head, "\xEF\xBB\xBF")) head.remove_prefix(3);
    if (trim(head).empty() && !cut) return FileKind::empty;
    if (starts_with(head, "AutoCAD Binary DXF")) return FileKind::dxf;
    if (starts_with(head, "%PDF-")) return FileKind::pdf;
    if (starts_with(head, "PK\x03\x04") || starts_with(head, "\x1f\x8b")) return FileKind::archive;
    if (cut || binary_text(head)) return FileKind::binary;
    const std::string_view start = trim(head);
    // Text that begins as JSON does is JSON with a mistake: its own error says where.
    if (start.front() == '{' || start.front() == '[') return FileKind::unknown;
    if (starts_with(start, "ISO-10303-21;")) return FileKind::step;
    if (ascii_dxf(head)) return FileKind::dxf;
    if (start.front() == '<') {
        if (contains_nocase(head, "<svg")) return FileKind::svg;
        if (contains_nocase(head, "<html") || starts_with_nocase(start, "<!DOCTYPE html")) return FileKind::html;
        if (starts_with(start, "<?xml")) return FileKind::xml;
    }
    if (starts_with_nocase(start, "solid") && contains_nocase(head, "facet normal")) return FileKind::stl;
    if (nc_program(head)) return FileKind::nc_program;
    return FileKind::unknown;
}

std::optional<std::string> not_json(std::string_view text, bool cut, const std::string& file, std::string_view expected,
                                    std::string_view machine) {
    const bool job = expected == "job";
    const std::string reads = job ? "camgen reads jobs in JSON (docs/job-format.md)"
                                  : "camgen reads machine files in JSON (docs/machine-files.md)";
    const auto drawing = [&](std::string_view what, std::string_view format) {
        return job ? fmt::format("{}, not a job: {}; {} import is not built yet", what, reads, format)
                   : fmt::format("{}, not a {}: {}", what, expected, reads);
    };
    switch (file_kind(text, cut)) {
        case FileKind::unknown: return std::nullopt;
        case FileKind::empty: return fmt::format("the file is empty: a {} is a JSON object ({})", expected,
                                                 job ? "docs/job-format.md" : "docs/machine-files.md");
        case FileKind::binary:
            return fmt::format("a binary file, not a {}: {}", expected,
                               job ? "camgen reads jobs in JSON text (docs/job-format.md)"
                                   : "camgen reads machine files in JSON text (docs/machine-files.md)");
        case FileKind::utf16:
            return fmt::format("a text in UTF-16: camgen reads a {} in UTF-8; save it as UTF-8", expected);
        case FileKind::dxf:
            return job ? fmt::format("a DXF drawing, not a job: {}; name the drawing in a job, as a drill's \"drawing\" or a contour's "
                                     "or pocket's \"profile\": {{\"dxf\": \"{}\", \"layer\": ...}}",
                                     reads, std::filesystem::path(file).filename().string())
                       : drawing("a DXF drawing", "DXF");
        case FileKind::svg: return drawing("an SVG drawing", "SVG");
        case FileKind::step: return drawing("a STEP model", "STEP");
        case FileKind::stl: return drawing("an STL mesh", "STL");
        case FileKind::html: return fmt::format("an HTML page, not a {}: {}", expected, reads);
        case FileKind::xml: return fmt::format("an XML document, not a {}: {}", expected, reads);
        case FileKind::pdf: return fmt::format("a PDF document, not a {}: {}", expected, reads);
        case FileKind::archive: return fmt::format("a ZIP or gzip archive, not a {}: unpack it; {}", expected, reads);
        case FileKind::nc_program:
            return fmt::format("this looks like an NC program, not a {}; to check it: camgen verify {} --machine {}",
                               expected, file == "<stdin>" ? "-" : file,
                               job && !machine.empty() ? std::string(machine) : std::string("M"));
    }
    return std::nullopt;
}

}  // namespace camgen
