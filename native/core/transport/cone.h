/// @file cone.h
/// @brief A round light seen from a point: a cone of directions of uniform radiance. Its
/// irradiance clipped by the surface's horizon, exactly, and directions spread uniformly over it
/// (internal; point, spot and sun lamps).
#pragma once

#include "common/stratified.h"
#include "common/types.h"

#include <glm/geometric.hpp>
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

/// Directions a cone's shadow gets where its first rays disagree (a penumbra): this squared.
constexpr int kPenumbraGrid = 16;
/// Directions at the cone's rim that look for a penumbra the first rays missed.
constexpr int kRimRays = 8;

/// The share of a round light's cone that nothing hides, seen from a surface of unit normal `n`:
/// over `grid` x `grid` directions stratified over the cone (jittered from `seed`), the sum of
/// cos(to n) * weight(u) of those that `visible(u)` finds unhidden over the sum of cos(to n) of all
/// above the surface; where they or kRimRays directions at the rim disagree and `grid` <
/// kPenumbraGrid, the same over kPenumbraGrid^2 directions. -1 when none lies above the surface.
template <typename Weight, typename Visible>
double lit_share(const Cone& cone, const glm::dvec3& n, int grid, uint32_t seed, Weight weight, Visible visible) {
    double cosines = 0.0, lit = 0.0;
    bool hidden = false, seen = false;
    for (int i = 0; i < grid * grid; ++i) {
        const double su = (i % grid + next_jitter(seed)) / grid, sv = (i / grid + next_jitter(seed)) / grid;
        const glm::dvec3 u = cone.direction(su, sv);
        const double c = glm::dot(n, u);
        if (!(c > 0.0)) continue;
        cosines += c;
        const double w = c * weight(u);
        if (!(w > 0.0)) continue;
        if (visible(u))
            lit += w, seen = true;
        else
            hidden = true;
    }
    if (grid < kPenumbraGrid && !(hidden && seen)) {  // a sliver seen or hidden at the rim only
        for (int k = 0; k < kRimRays && !(hidden && seen); ++k) {
            const glm::dvec3 u = cone.direction(0.999, (k + next_jitter(seed)) / kRimRays);
            if (glm::dot(n, u) > 0.0 && weight(u) > 0.0) (visible(u) ? seen : hidden) = true;
        }
    }
    if (hidden && seen && grid < kPenumbraGrid) return lit_share(cone, n, kPenumbraGrid, seed, weight, visible);
    return cosines > 0.0 ? lit / cosines : -1.0;
}

/// A seed from a point's position, so that the same point gets the same rays on any thread.
uint32_t position_seed(const Vec3& x, uint32_t salt);

}  // namespace radiosity::detail
