#include <stiffsoft/libfem/lame_parameters.hpp>

#include <gtest/gtest.h>

#include <string>

#include <stiffsoft/libfem/make_material.hpp>
#include <stiffsoft/libfem/stable_neo_hookean.hpp>

using namespace stiffsoft::fem;

namespace {
std::string message_of(void (*f)()) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(LameParameters, FollowFromYoungsModulusAndPoissonRatio) {
  // E = 2.6 Pa, ν = 0.3: μ = 2.6/2.6 = 1, λ = 2.6·0.3/(1.3·0.4) = 1.5.
  const LameParameters p = lame_parameters(2.6, 0.3);
  EXPECT_NEAR(p.mu, 1.0, 1e-15);
  EXPECT_NEAR(p.lambda, 1.5, 1e-15);
  // ν = 0: λ = 0, μ = E/2.
  EXPECT_EQ(lame_parameters(4.0, 0.0).lambda, 0.0);
  EXPECT_EQ(lame_parameters(4.0, 0.0).mu, 2.0);
}

TEST(LameParameters, ErrorsNameTheValueAndTheExpectedRange) {
  EXPECT_EQ(message_of([] { lame_parameters(1e6, 0.5); }),
            "libfem: Poisson ratio nu = 0.5 is invalid; expected -1 < nu < 0.5");
  EXPECT_EQ(message_of([] { lame_parameters(-3, 0.3); }),
            "libfem: Young's modulus E = -3 Pa is invalid; expected a finite E > 0");
  EXPECT_EQ(message_of([] { check_density(0); }),
            "libfem: density rho = 0 kg/m^3 is invalid; expected a finite rho > 0");
  EXPECT_NE(message_of([] { lame_parameters(1e6, -1); }), "");
  EXPECT_NE(message_of([] { lame_parameters(1e6, 0.5000000001); }).find("nu = 0.5000000001 "),
            std::string::npos);
  EXPECT_NO_THROW(lame_parameters(1e6, 0.4999999999));
  EXPECT_NE(message_of([] { lame_parameters(0, 0.3); }), "");
  EXPECT_NE(message_of([] { check_density(-1000); }), "");
  EXPECT_NO_THROW(check_density(1000));
}

TEST(MaterialFactory, UnknownNameListsTheValidOnes) {
  const std::string message = message_of([] { make_material("neo_hookean", 1e6, 0.3); });
  EXPECT_NE(message.find("\"neo_hookean\""), std::string::npos) << message;
  for (const char* name : {"\"linear\"", "\"fixed_corotated\"", "\"stable_neo_hookean\""})
    EXPECT_NE(message.find(name), std::string::npos) << message;
}

TEST(MaterialFactory, NamesRoundTrip) {
  for (const char* name : {"linear", "fixed_corotated", "stable_neo_hookean"}) {
    const auto material = make_material(name, 1e6, 0.3);
    EXPECT_STREQ(material->name(), name);
    EXPECT_EQ(material->youngs_modulus(), 1e6);
    EXPECT_EQ(material->poisson_ratio(), 0.3);
  }
}

TEST(StableNeoHookean, UsesTheReparameterisedLameConstants) {
  const StableNeoHookean m(2.6, 0.3);  // μ = 1, λ = 1.5
  EXPECT_NEAR(m.mu_hat(), 1.0, 1e-15);
  EXPECT_NEAR(m.lambda_hat(), 2.5, 1e-15);
  EXPECT_NEAR(m.alpha(), 1.4, 1e-15);
}
