#pragma once
// What a file is that camgen expected to be JSON and could not parse: a drawing, a model, an
// NC program, a binary file, nothing at all. Said by the first bytes and lines, only after the
// JSON parse failed, so that a valid file is never misjudged.
#include <optional>
#include <string>
#include <string_view>

namespace camgen {

enum class FileKind {
    unknown,      // maybe JSON with a mistake: the JSON error says more
    empty,        // nothing, or only white space
    binary,       // NUL bytes or mostly control characters
    utf16,        // text with a UTF-16 byte order mark
    dxf,          // a DXF drawing (ASCII or binary)
    svg,          // an SVG drawing
    html,         // an HTML page
    xml,          // another XML document
    step,         // a STEP model (ISO 10303-21)
    stl,          // an STL mesh (ASCII)
    pdf,          // a PDF document
    archive,      // a ZIP or gzip archive
    nc_program,   // G-code, an nccad .knc, a Heidenhain conversational program
};

// The kind of `text` (its first 64 KiB are enough). `cut`: the reader dropped text after a NUL
// byte (binary).
FileKind file_kind(std::string_view text, bool cut = false);

// The message for a file that is not the JSON `expected` ("job" or "machine file") although
// it was given as one, with what the user probably meant; none where file_kind says unknown.
// `file` names it in the suggested command, `machine` is the --machine given ("" : none).
std::optional<std::string> not_json(std::string_view text, bool cut, const std::string& file,
                                    std::string_view expected, std::string_view machine = {});

}  // namespace camgen
