#include <stiffsoft/study/order_fit.hpp>

#include <cmath>
#include <limits>

namespace stiffsoft::study {

std::optional<LogLogFit> fit_log_log(const std::vector<double>& x, const std::vector<double>& e) {
  std::vector<double> lx, le;
  for (std::size_t i = 0; i < x.size() && i < e.size(); ++i)
    if (std::isfinite(x[i]) && std::isfinite(e[i]) && x[i] > 0 && e[i] > 0) {
      lx.push_back(std::log(x[i]));
      le.push_back(std::log(e[i]));
    }
  if (lx.size() < 2) return std::nullopt;
  const double n = double(lx.size());
  double mx = 0, me = 0;
  for (std::size_t i = 0; i < lx.size(); ++i) mx += lx[i] / n, me += le[i] / n;
  double sxx = 0, sxe = 0;
  for (std::size_t i = 0; i < lx.size(); ++i) {
    sxx += (lx[i] - mx) * (lx[i] - mx);
    sxe += (lx[i] - mx) * (le[i] - me);
  }
  if (!(sxx > 0)) return std::nullopt;
  LogLogFit fit;
  fit.slope = sxe / sxx;
  fit.intercept = me - fit.slope * mx;
  fit.points = int(lx.size());
  return fit;
}

Eigen::VectorXd richardson_extrapolate(const Eigen::VectorXd& f1, const Eigen::VectorXd& f2, double r, double p) {
  return f1 + (f1 - f2) / (std::pow(r, p) - 1.0);
}

double three_point_order(const Eigen::VectorXd& f1, const Eigen::VectorXd& f2, const Eigen::VectorXd& f3, double r) {
  const double d21 = (f2 - f1).norm(), d32 = (f3 - f2).norm();
  if (!(d21 > 0) || !(d32 > 0)) return std::numeric_limits<double>::quiet_NaN();
  return std::log(d32 / d21) / std::log(r);
}

}  // namespace stiffsoft::study
