/// @file cone.h
/// @brief A round light seen from a point: a cone of directions of uniform radiance. Its
/// irradiance clipped by the surface's horizon, exactly, and directions spread uniformly over it
/// (internal; point, spot and sun lamps).
#pragma once

#include "common/types.h"

#include <glm/vec3.hpp>

namespace radiosity::detail {

/// The integral of max(0, cos to the normal) over a cone of half-angle sigma (`sin2_sigma` =
/// sin^2 sigma, 1 or more: the whole hemisphere) whose axis makes an angle of cosine `cos_theta`
/// with the normal: the irradiance of a unit-radiance sphere or disk filling that cone, with the
/// part below the horizon clipped. Snyder 1996, "Area light sources for real-time graphics"
/// (Microsoft Research MSR-TR-96-11), in the form of Lagarde and de Rousiers 2014, "Moving
/// Frostbite to PBR", listing 7: pi sin^2 sigma cos theta while the cone is above the horizon.
double clipped_cone_cosine(double cos_theta, double sin2_sigma);

/// A cone of directions about a unit axis and its frame.
struct Cone {
    glm::dvec3 axis, t, b;
    double cos_max = 1.0;  ///< cosine of the half-angle

    Cone(const glm::dvec3& unit_axis, double cos_half_angle);
    /// The direction for (u, v) in the unit square, uniform in solid angle over the cone: cos theta
    /// uniform in [cos_max, 1] (Shirley, Wang and Zimmerman 1996, "Monte Carlo techniques for
    /// direct lighting calculations", ACM TOG 15(1), section 3.2).
    glm::dvec3 direction(double u, double v) const;
};

/// A seed from a point's position, so that the same point gets the same rays on any thread.
uint32_t position_seed(const Vec3& x, uint32_t salt);

}  // namespace radiosity::detail
