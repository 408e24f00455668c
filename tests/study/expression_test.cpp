/// @file The analytic-reference expression language (stiffsoft/study/expression.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <stiffsoft/study/builtin_references.hpp>
#include <stiffsoft/study/expression.hpp>

using stiffsoft::study::evaluate;

TEST(StudyExpression, ArithmeticPrecedenceAndPower) {
  EXPECT_DOUBLE_EQ(evaluate("1 + 2 * 3", {}), 7.0);
  EXPECT_DOUBLE_EQ(evaluate("(1 + 2) * 3", {}), 9.0);
  EXPECT_DOUBLE_EQ(evaluate("2^3^2", {}), 512.0);  // right-associative
  EXPECT_DOUBLE_EQ(evaluate("-2^2", {}), -4.0);
  EXPECT_DOUBLE_EQ(evaluate("2^-1", {}), 0.5);
  EXPECT_DOUBLE_EQ(evaluate("1e-3 * 4 / 2", {}), 2e-3);
  EXPECT_DOUBLE_EQ(evaluate("8 - 3 - 2", {}), 3.0);  // left-associative
}

TEST(StudyExpression, VariablesAndFunctions) {
  const stiffsoft::study::Variables v{{"t", 2.0}, {"omega", 0.5}};
  EXPECT_DOUBLE_EQ(evaluate("cos(omega * t)", v), std::cos(1.0));
  EXPECT_DOUBLE_EQ(evaluate("atan2(1, 1)", v), std::numbers::pi / 4);
  EXPECT_DOUBLE_EQ(evaluate("max(t, 3) + min(t, 3)", v), 5.0);
  EXPECT_DOUBLE_EQ(evaluate("sqrt(abs(-16)) + pi", v), 4.0 + std::numbers::pi);
}

TEST(StudyExpression, ErrorsNameTheExpressionAndWhat) {
  try {
    evaluate("2 * tt", {{"t", 1.0}});
    FAIL() << "unknown variable accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown name 'tt'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2 * tt"), std::string::npos) << e.what();
  }
  EXPECT_THROW(evaluate("(1 + 2", {}), std::invalid_argument);
  EXPECT_THROW(evaluate("1 +", {}), std::invalid_argument);
  EXPECT_THROW(evaluate("sin(1, 2)", {}), std::invalid_argument);
  EXPECT_THROW(evaluate("foo(1)", {}), std::invalid_argument);
  EXPECT_THROW(evaluate("1 2", {}), std::invalid_argument);
}

// The built-in references evaluate to the numbers of validation.md.
TEST(StudyExpression, BuiltinReferencesMatchValidationNumbers) {
  const auto* incline = stiffsoft::study::find_builtin_reference("incline_sliding_distance");
  ASSERT_NE(incline, nullptr);
  const double s = evaluate(incline->expressions[0], {{"g", 9.81}, {"theta", std::atan(0.5)}, {"mu", 0.49}, {"t", 2.5}});
  EXPECT_NEAR(s, 0.274, 0.0005);  // validation.md: s(2.5 s) ≈ 0.274 m
  const auto* growth = stiffsoft::study::find_builtin_reference("intermediate_axis_growth_rate");
  ASSERT_NE(growth, nullptr);
  // Box 1 × 0.5 × 0.1 m, 1 kg, Ω = 10 rad/s → λ ≈ 7.44 s⁻¹.
  const double I1 = (0.25 + 0.01) / 12, I2 = (1 + 0.01) / 12, I3 = (1 + 0.25) / 12;
  EXPECT_NEAR(evaluate(growth->expressions[0], {{"Omega", 10}, {"I1", I1}, {"I2", I2}, {"I3", I3}}), 7.44, 0.005);
  const auto* hertz = stiffsoft::study::find_builtin_reference("hertz_force");
  ASSERT_NE(hertz, nullptr);
  // docs/validation_hertz.md: k = (4/3) E* √R = 3.276e5 N/m^1.5 for E = 1 MPa, ν = 0.3, R = 0.05 m.
  EXPECT_NEAR(evaluate(hertz->expressions[0], {{"E", 1e6}, {"nu", 0.3}, {"R", 0.05}, {"delta", 1.0}}), 3.276e5, 50);
}
