#pragma once
/// @file A small arithmetic expression language for analytic references in study files,
/// e.g. `0.5 * g * (sin(theta) - mu * cos(theta)) * t^2`.

#include <map>
#include <string>

namespace stiffsoft::study {

/// Named values an expression may use (study constants, the time t of the quantity, the
/// swept parameters). `pi` is always defined.
using Variables = std::map<std::string, double>;

/// Evaluates `text`: numbers (1, 2.5, 1e-3), variables, + − * / ^ (right-associative power),
/// unary minus, parentheses, and the functions sqrt, exp, log, sin, cos, tan, asin, acos,
/// atan, abs, cbrt (one argument) and atan2, pow, min, max (two arguments).
/// Throws std::invalid_argument naming the expression and the offending position on a
/// syntax error, an unknown variable or function, or a wrong argument count.
double evaluate(const std::string& text, const Variables& variables);

}  // namespace stiffsoft::study
