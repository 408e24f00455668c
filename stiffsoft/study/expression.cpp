#include <stiffsoft/study/expression.hpp>

#include <cctype>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace stiffsoft::study {

namespace {

/// Recursive-descent parser that evaluates while it parses.
class Parser {
 public:
  Parser(const std::string& text, const Variables& variables) : text_(text), variables_(variables) {}

  double parse() {
    const double value = sum();
    skip_space();
    if (pos_ != text_.size()) fail("unexpected '" + std::string(1, text_[pos_]) + "'");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("expression '" + text_ + "', at character " + std::to_string(pos_ + 1) + ": " + what);
  }
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool accept(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  // sum := product (('+'|'-') product)*
  double sum() {
    double value = product();
    for (;;) {
      if (accept('+')) value += product();
      else if (accept('-')) value -= product();
      else return value;
    }
  }
  // product := unary (('*'|'/') unary)*
  double product() {
    double value = unary();
    for (;;) {
      if (accept('*')) value *= unary();
      else if (accept('/')) value /= unary();
      else return value;
    }
  }
  // unary := '-' unary | '+' unary | power
  double unary() {
    if (accept('-')) return -unary();
    if (accept('+')) return unary();
    return power();
  }
  // power := primary ('^' unary)?   (right-associative; -2^2 = -4, 2^-1 = 0.5)
  double power() {
    const double base = primary();
    if (accept('^')) return std::pow(base, unary());
    return base;
  }
  double primary() {
    skip_space();
    if (pos_ >= text_.size()) fail("expected a number, a name or '('");
    if (accept('(')) {
      const double value = sum();
      if (!accept(')')) fail("expected ')'");
      return value;
    }
    const char c = text_[pos_];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') return name();
    fail("unexpected '" + std::string(1, c) + "'");
  }
  double number() {
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin) fail("malformed number");
    pos_ += std::size_t(end - begin);
    return value;
  }
  double name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_')) ++pos_;
    const std::string id = text_.substr(start, pos_ - start);
    if (accept('(')) {
      std::vector<double> args;
      if (!accept(')')) {
        do args.push_back(sum());
        while (accept(','));
        if (!accept(')')) fail("expected ')' after the arguments of " + id);
      }
      return call(id, args);
    }
    if (const auto it = variables_.find(id); it != variables_.end()) return it->second;
    if (id == "pi") return std::numbers::pi;
    pos_ = start;
    fail("unknown name '" + id + "'");
  }
  double call(const std::string& id, const std::vector<double>& a) {
    static const std::map<std::string, std::function<double(double)>> one{
        {"sqrt", [](double x) { return std::sqrt(x); }}, {"exp", [](double x) { return std::exp(x); }},
        {"log", [](double x) { return std::log(x); }},   {"sin", [](double x) { return std::sin(x); }},
        {"cos", [](double x) { return std::cos(x); }},   {"tan", [](double x) { return std::tan(x); }},
        {"asin", [](double x) { return std::asin(x); }}, {"acos", [](double x) { return std::acos(x); }},
        {"atan", [](double x) { return std::atan(x); }}, {"abs", [](double x) { return std::abs(x); }},
        {"cbrt", [](double x) { return std::cbrt(x); }}};
    static const std::map<std::string, std::function<double(double, double)>> two{
        {"atan2", [](double y, double x) { return std::atan2(y, x); }},
        {"pow", [](double x, double y) { return std::pow(x, y); }},
        {"min", [](double x, double y) { return std::min(x, y); }},
        {"max", [](double x, double y) { return std::max(x, y); }}};
    if (const auto it = one.find(id); it != one.end()) {
      if (a.size() != 1) fail(id + "() takes 1 argument, got " + std::to_string(a.size()));
      return it->second(a[0]);
    }
    if (const auto it = two.find(id); it != two.end()) {
      if (a.size() != 2) fail(id + "() takes 2 arguments, got " + std::to_string(a.size()));
      return it->second(a[0], a[1]);
    }
    fail("unknown function '" + id + "'");
  }

  const std::string& text_;
  const Variables& variables_;
  std::size_t pos_ = 0;
};

}  // namespace

double evaluate(const std::string& text, const Variables& variables) { return Parser(text, variables).parse(); }

}  // namespace stiffsoft::study
