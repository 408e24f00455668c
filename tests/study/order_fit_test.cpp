/// @file Observed orders and Richardson extrapolation (stiffsoft/study/order_fit.hpp).

#include <gtest/gtest.h>

#include <cmath>

#include <stiffsoft/study/order_fit.hpp>

using namespace stiffsoft::study;

TEST(StudyOrderFit, RecoversThePowerOfAPowerLaw) {
  const std::vector<double> x{0.1, 0.05, 0.025, 0.0125};
  std::vector<double> e;
  for (double h : x) e.push_back(3.0 * h * h);
  const auto fit = fit_log_log(x, e);
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->slope, 2.0, 1e-12);
  EXPECT_NEAR(std::exp(fit->intercept), 3.0, 1e-10);
  EXPECT_EQ(fit->points, 4);
}

TEST(StudyOrderFit, SkipsZeroAndNonFiniteErrorsAndNeedsTwoPoints) {
  const auto fit = fit_log_log({1, 2, 4, 8}, {0.0, 2.0, NAN, 8.0});
  ASSERT_TRUE(fit);
  EXPECT_EQ(fit->points, 2);
  EXPECT_NEAR(fit->slope, 1.0, 1e-12);
  EXPECT_FALSE(fit_log_log({1, 2}, {1.0, 0.0}));
  EXPECT_FALSE(fit_log_log({2, 2}, {1.0, 3.0}));
}

// f(h) = f* + C h^p: Richardson with the right order gives f* exactly; three values give p.
TEST(StudyOrderFit, RichardsonRemovesTheLeadingTerm) {
  const double exact = 1.5, C = 0.7, p = 2;
  auto f = [&](double h) { return Eigen::VectorXd::Constant(1, exact + C * std::pow(h, p)); };
  EXPECT_NEAR(richardson_extrapolate(f(0.01), f(0.02), 2.0, p)[0], exact, 1e-14);
  EXPECT_NEAR(three_point_order(f(0.01), f(0.02), f(0.04), 2.0), p, 1e-9);
  // A second term C₂ h³ leaves an O(h³) error in the extrapolation.
  auto g = [&](double h) { return Eigen::VectorXd::Constant(1, exact + C * h * h + 5 * h * h * h); };
  const double err = std::abs(richardson_extrapolate(g(0.01), g(0.02), 2.0, 2.0)[0] - exact);
  EXPECT_GT(err, 0);
  EXPECT_LT(err, 5 * 0.01 * 0.01 * 0.01 * 2.1);
  EXPECT_TRUE(std::isnan(three_point_order(f(0.01), f(0.01), f(0.04), 2.0)));
}
