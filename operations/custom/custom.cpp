#include "camgen/operations/custom/custom.hpp"

#include <fmt/format.h>

#include "camgen/common/error.hpp"

namespace camgen {

namespace {

using Fields = json::Fields;

constexpr KeySpec custom_keys[] = {
    {.key = "type", .type = JsonType::string, .required = true, .description = "the kind of operation"},
    {.key = "text", .type = JsonType::object, .required = true,
     .description = "the lines to write, by machine name or dialect name (iso, iso-lathe, nccad, sinumerik, "
                    "sinumerik-lathe, heidenhain): a string (one line) or an array of lines; \"\" or []: nothing for "
                    "that machine. A machine's own name comes before its dialect's; a machine with neither is refused"},
    {.key = "comment", .type = JsonType::string, .default_json = "\"\"",
     .description = "written as a comment before the block"},
};

// Why `line` cannot be a line of a program: what the comments and blocks camgen writes never
// hold (control bytes end or split a block on some controls and DNC links, '%' ends a Fanuc
// program's record, characters outside ASCII are read differently by each control).
std::optional<std::string> line_problem(std::string_view line) {
    if (line.find_first_not_of(' ') == std::string_view::npos)
        return "an empty line: give the lines to write, or \"\" for none";
    if (line.size() > max_custom_line)
        return fmt::format("a line of {} characters, more than {}", line.size(), max_custom_line);
    for (const char c : line) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7F) return "a control character (a line break, a tab, ...): give one line per array item";
        if (u >= 0x80) return "a character outside ASCII: controls read those differently";
        if (c == '%') return "'%': a Fanuc-style control ends the program's record there";
    }
    return std::nullopt;
}

}  // namespace

std::vector<ObjectSpec> CustomOp::objects() {
    return {{.name = "custom",
             .description = "lines of the control's own language, written as they are where the machine's reader reads "
                            "them back and they neither move the tool nor change the machine's state",
             .keys = {std::begin(custom_keys), std::end(custom_keys)}}};
}

CustomOp CustomOp::read(Fields& f, const JobInput& in) {
    JobInput::known_keys(f, custom_keys);
    CustomOp op;
    op.path = f.path();
    op.comment = f.optional_string("comment").value_or("");
    const nlohmann::json& text = f.required("text");
    const std::string text_path = f.path_of("text");
    if (!text.is_object()) f.fail("text", "text is an object: the lines by machine or dialect name");
    if (text.empty()) f.fail("text", "text names no machine or dialect");
    for (auto it = text.begin(); it != text.end(); ++it) {
        const std::string path = text_path + "/" + json::pointer_escape(it.key());
        if (it.key().empty()) json::fail(in.source(), path, "an empty machine or dialect name");
        CustomText t{it.key(), {}};
        auto add = [&](const nlohmann::json& line, const std::string& line_path) {
            if (!line.is_string())
                json::fail(in.source(), line_path, fmt::format("a line is a string, not {}", JobInput::describe(line)));
            const std::string s = line.get<std::string>();
            if (auto problem = line_problem(s)) json::fail(in.source(), line_path, "custom text: " + *problem);
            t.lines.push_back(s);
        };
        if (it->is_string()) {
            if (!it->get<std::string>().empty()) add(*it, path);
        } else if (it->is_array()) {
            if (it->size() > max_custom_lines)
                json::fail(in.source(), path, fmt::format("{} lines, more than {}", it->size(), max_custom_lines));
            for (std::size_t i = 0; i < it->size(); ++i) add((*it)[i], path + "/" + std::to_string(i));
        } else {
            json::fail(in.source(), path,
                       fmt::format("the lines for {} are a string or an array of strings, not {}", it.key(),
                                   JobInput::describe(*it)));
        }
        op.texts.push_back(std::move(t));
    }
    return op;
}

void expand(const CustomOp& op, const Context&, EventSink& sink) { sink.emit(CustomBlock{op.texts, op.path + "/text"}); }

std::string default_name(const CustomOp& op) { return op.comment.empty() ? "custom block" : op.comment; }

}  // namespace camgen
