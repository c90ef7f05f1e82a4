#pragma once
// Visiting camgen's variants (events, operations, path elements) exhaustively: every
// alternative is handled by an overload that names it. A visitor that misses an alternative,
// or that has a catch-all (a generic lambda) that would swallow a new alternative silently,
// does not compile. Every visit in camgen goes through visit_exhaustive.
#include <cstddef>
#include <type_traits>
#include <utility>
#include <variant>

namespace camgen {

// Lambdas joined into one overload set.
template <class... Ts>
struct overloaded : Ts... {
    using Ts::operator()...;
};
template <class... Ts>
overloaded(Ts...) -> overloaded<Ts...>;

namespace detail {
// A type no variant holds: a visitor callable with it has a catch-all.
struct NotAnAlternative {};

// `Variant` as visited (const or not, lvalue or rvalue): each alternative as std::visit passes it.
template <class Visitor, class Variant, std::size_t... I>
constexpr bool handles_all(std::index_sequence<I...>) {
    return (std::is_invocable_v<Visitor, decltype(std::get<I>(std::declval<Variant>()))> && ...);
}
}  // namespace detail

// True when `Visitor` names every alternative of `Variant` and has no catch-all.
template <class Visitor, class Variant>
inline constexpr bool is_exhaustive_visitor =
    !std::is_invocable_v<Visitor, const detail::NotAnAlternative&> &&
    detail::handles_all<Visitor, const Variant&>(std::make_index_sequence<std::variant_size_v<Variant>>());

// std::visit, refused at compile time unless the visitor is exhaustive (see above).
template <class Visitor, class Variant>
decltype(auto) visit_exhaustive(Visitor&& visitor, Variant&& variant) {
    using V = std::remove_cvref_t<Variant>;
    static_assert(!std::is_invocable_v<Visitor, const detail::NotAnAlternative&>,
                  "camgen visitor has a catch-all overload: name every alternative instead");
    static_assert(detail::handles_all<Visitor, Variant&&>(std::make_index_sequence<std::variant_size_v<V>>()),
                  "camgen visitor does not handle every alternative of the variant");
    return std::visit(std::forward<Visitor>(visitor), std::forward<Variant>(variant));
}

}  // namespace camgen
