/// @file lamps_in_media.h
/// @brief Point, spot and sun lamps in a bake with media: the zonal system's first shot. Their
/// direct light on the elements, dimmed by the media between, and on the zones, the source of the
/// media's single scattering (Rushmeier & Torrance 1987's zone equation with the lamps' direct
/// irradiance as a known term).
///
/// A zone k of extinction K_t and volume V takes up, from a lamp of intensity I (irradiance
/// I cos / r^2, as point_light.h),
///   P_k = I integral over the directions through k of tau_before (1 - tau_k)
///       = I K_t integral over k of tau(lamp, x) / |x - lamp|^2 dx            (dV = r^2 dr d omega),
/// and its mean incident radiance is H_k = P_k / (4 pi K_t V) (media_bake.h's zone equation), so
///   H_k = I / (4 pi) * mean over x in k of tau(lamp, x) visible(lamp, x) profile / |x - lamp|^2.
/// A sun of irradiance E gives H_k = E / (4 pi) * mean over x in k of tau(x, sun) visible(x, sun).
/// The mean over the zone is taken at the midpoints of its 3^3 sub-cubes (the midpoint rule: exact
/// for light linear across the zone, within 0.7% for a point lamp two zone edges away). Zones
/// nearer a lamp than two of their edges, where 1 / |x - lamp|^2 varies too much across the zone
/// for that, take the first form instead, from stratified directions out of the lamp (a
/// spherical Fibonacci lattice of 32,768), each walked through the media to the first surface.
///
/// Lamps are points here: a lamp's radius shapes its light on the elements (direct_irradiance)
/// but not the transmittance to it, taken along the ray from the element's centre to the lamp's
/// centre, nor its light on the zones.
#pragma once

#include "media/transmittance.h"
#include "transport/lights.h"

#include <vector>

namespace radiosity {

struct LampsThroughMedia {
    /// Per element, the lamps' irradiance as direct_irradiance gives it, each lamp's times the
    /// transmittance from the element's centre to it.
    std::vector<Rgb> element_irradiance;
    /// Per zone, H_k: the lamps' light taken up there as the mean incident radiance over the
    /// zone and all directions.
    std::vector<Rgb> zone_incident;
};

/// The lamps' direct light on `elements` and `zones` (the zones of the media `tracer` walks), shadows
/// from the elements included. Progress phase "lights" (once per lamp over the elements); throws
/// Cancelled.
LampsThroughMedia lamps_through_media(const Elements& elements, const Lights& lights, const Zones& zones,
                                      const MediumTracer& tracer, const ProgressFn& progress = {});

}  // namespace radiosity
