#include "camgen/common/error.hpp"

#include <stdexcept>
#include <utility>

namespace camgen {

InputError::InputError(std::string path, std::string detail, int line, std::string source)
    : std::runtime_error(compose(source, line, path, detail)),
      path_(std::move(path)),
      detail_(std::move(detail)),
      line_(line),
      source_(std::move(source)) {}

InputError::InputError(const InputError& first, const std::string& message)
    : std::runtime_error(message),
      path_(first.path_),
      detail_(first.detail_),
      line_(first.line_),
      source_(first.source_) {}

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

namespace {
// The first error, for the base class; the list must not be empty.
const InputError& first_of(const std::vector<InputError>& errors) {
    if (errors.empty()) throw std::logic_error("InputErrors of no error");
    return errors.front();
}
}  // namespace

InputErrors::InputErrors(std::vector<InputError> errors, std::size_t not_kept)
    : InputError(first_of(errors), list(errors, errors.size() + not_kept)), count_(errors.size() + not_kept) {
    if (errors.size() > shown) errors.erase(errors.begin() + static_cast<std::ptrdiff_t>(shown), errors.end());
    errors_ = std::move(errors);
}

// The first `shown` errors' messages, one a line, and how many more there are.
std::string InputErrors::list(const std::vector<InputError>& errors, std::size_t count) {
    std::string text;
    std::size_t listed = 0;
    for (; listed < errors.size() && listed < shown; ++listed) {
        if (listed > 0) text += '\n';
        text += errors[listed].what();
    }
    if (count > listed) text += "\nand " + std::to_string(count - listed) + " more error" + (count - listed == 1 ? "" : "s");
    return text;
}

}  // namespace camgen
