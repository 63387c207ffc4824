/// @file test_cone.cpp
/// @brief The clipped cone's irradiance against a sum over rings of directions about the normal.
#include "transport/cone.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>

namespace radiosity {
namespace {

/// The integral of max(0, n . w) over directions w within `sigma` of `axis` (in the xz-plane at
/// `alpha` from the normal z): over rings of polar angle theta about z, each contributing
/// cos theta sin theta times the azimuth it spends inside the cone, by the midpoint rule.
double by_rings(double alpha, double sigma) {
    constexpr int kRings = 400000;
    double sum = 0.0;
    for (int i = 0; i < kRings; ++i) {
        const double theta = (i + 0.5) * (M_PI / 2) / kRings;
        const double s = std::sin(theta) * std::sin(alpha);
        const double c = std::cos(sigma) - std::cos(theta) * std::cos(alpha);
        double azimuth = 0.0;
        if (s <= std::abs(c))
            azimuth = c <= 0.0 ? 2.0 * M_PI : 0.0;
        else
            azimuth = 2.0 * std::acos(c / s);
        sum += std::cos(theta) * std::sin(theta) * azimuth;
    }
    return sum * (M_PI / 2) / kRings;
}

TEST(ClippedCone, MatchesItsRingsAboveAcrossAndBelowTheHorizon) {
    for (double sigma : {0.1, 0.5, 1.0, 1.4}) {
        for (double theta : {0.0, 0.7, 1.2, 1.5, 1.7, 2.2}) {
            const double exact = detail::clipped_cone_cosine(std::cos(theta), std::sin(sigma) * std::sin(sigma));
            EXPECT_NEAR(exact, by_rings(theta, sigma), 1e-6 * std::max(1.0, exact)) << sigma << " " << theta;
        }
    }
}

TEST(ClippedCone, WholeSphereIsPi) { EXPECT_DOUBLE_EQ(detail::clipped_cone_cosine(0.3, 1.0), M_PI); }

TEST(Cone, DirectionsStayInsideAndCoverTheCone) {
    const detail::Cone cone(glm::normalize(glm::dvec3(1, 2, 3)), std::cos(0.4));
    double mean_cos = 0.0;
    constexpr int kSide = 64;
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j) {
            const glm::dvec3 u = cone.direction((i + 0.5) / kSide, (j + 0.5) / kSide);
            EXPECT_NEAR(glm::length(u), 1.0, 1e-12);
            EXPECT_GE(glm::dot(u, cone.axis), std::cos(0.4) - 1e-12);
            mean_cos += glm::dot(u, cone.axis) / (kSide * kSide);
        }
    EXPECT_NEAR(mean_cos, (1.0 + std::cos(0.4)) / 2.0, 1e-9);  // cos theta uniform over [cos 0.4, 1]
}

}  // namespace
}  // namespace radiosity
