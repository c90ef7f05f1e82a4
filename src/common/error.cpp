#include "camgen/common/error.hpp"

#include <utility>

namespace camgen {

InputError::InputError(std::string path, std::string detail, int line, std::string source)
    : std::runtime_error(compose(source, line, path, detail)),
      path_(std::move(path)),
      detail_(std::move(detail)),
      line_(line),
      source_(std::move(source)) {}

InputError InputError::located(std::string source, int line) const {
    return InputError(path_, detail_, line, std::move(source));
}

// "SOURCE:LINE: PATH: DETAIL", leaving out the parts that are empty.
std::string InputError::compose(const std::string& source, int line, const std::string& path,
                                const std::string& detail) {
    std::string where_text = source;
    if (line > 0) {
        where_text += where_text.empty() ? "line " : ":";
        where_text += std::to_string(line);
    }
    const std::string& where = where_text;
    std::string text;
    for (const std::string* part : {&where, &path, &detail}) {
        if (part->empty()) continue;
        if (!text.empty()) text += ": ";
        text += *part;
    }
    return text;
}

}  // namespace camgen
