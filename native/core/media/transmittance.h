/// @file transmittance.h
/// @brief Transmittance tau = exp(-integral K_t ds) along a ray through the zone grids, with the
/// fraction of the ray's light each zone removes (3D-DDA, Amanatides & Woo).
///
/// The walk multiplies tau by exp(-K_t,k s_k) in every zone k it crosses for length s_k and
/// credits k with tau_before - tau_after. The credits telescope, so per ray and channel
///   tau_end + sum of credits = 1
/// up to float rounding: light that leaves a ray is taken up by exactly one zone (energy is
/// conserved by construction). A zone's credit is also what it adds to the radiance seen along the
/// ray when it has uniform radiance J_k: the zonal method's ray integral (Rushmeier & Torrance 1987) in zone k gives
/// J_k times it.
#pragma once

#include "media/volume.h"

#include <glm/vec3.hpp>

#include <vector>

namespace radiosity {

using Channels = glm::vec3;  ///< per-RGB-channel fractions along one ray (float: one per cell)

/// Zone `zone` took `fraction` of the light that entered the ray.
struct ZoneCredit {
    int32_t zone;
    Channels fraction;
};

/// Walks rays through the zones of a set of media, voxel by voxel, crediting each voxel's zone. Read-only after
/// construction: share it between threads.
class MediumTracer {
public:
    /// `zones` must be build_zones(media); the tracer keeps no reference to either.
    MediumTracer(const std::vector<Medium>& media, const Zones& zones);

    /// Transmittance from `origin` to origin + t_max * direction (`direction` unit; t_max may be
    /// infinite), replacing `credits` with the zones crossed in ray order (one credit per stretch in a zone). The walk
    /// stops early once tau < 1e-7 in every channel; the returned tau still closes the sum to 1.
    Channels trace(const Vec3& origin, const Vec3& direction, float t_max, std::vector<ZoneCredit>& credits) const;

private:
    struct Grid {
        Vec3 origin{0.0f};
        float h = 0.0f;
        std::array<int32_t, 3> dims{0, 0, 0}, lo{0, 0, 0}, hi{0, 0, 0};
        Vec3 world_lo{0.0f}, world_hi{0.0f};
        std::vector<int32_t> zone;  ///< per voxel, its zone (voxel_zones), -1 where empty
    };
    void walk(const Grid& grid, const Vec3& origin, const Vec3& direction, float t0, float t1, Channels& tau,
              std::vector<ZoneCredit>& credits) const;

    std::vector<Grid> grids_;
    std::vector<Channels> extinction_;  ///< K_t per zone
};

}  // namespace radiosity
