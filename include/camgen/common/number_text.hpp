#pragma once
// Numbers in messages (errors, warnings, notes): rounded, never the float's full expansion
// (0.12000000000000001), never an exponent or "-0".
#include <string>

namespace camgen {

// `value` with at most `decimals` decimals (default 4), trailing zeros and a trailing point
// dropped: 0.12000000000000001 -> "0.12", 2.5 -> "2.5", 1000 -> "1000", -0.00001 -> "-0.00001".
// A small value (below 10^(1 - decimals)) keeps its first two significant digits (up to 12
// decimals), so that "feed 0.00001 mm/min would be written as F0" does not say "feed 0" and
// 0.00008 is not "0.0001". Not finite: "nan", "inf", "-inf".
std::string number_text(double value, int decimals = 4);

}  // namespace camgen
