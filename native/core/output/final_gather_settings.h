/// @file final_gather_settings.h
/// @brief What the final gather at the output corners does, and how many rays it spends.
#pragma once

namespace radiosity {

/// A final gather at the output corners (off by default): each input corner's radiance is computed
/// at the corner itself, L(x) = L_e(x) + rho(x) [direct(x) + indirect(x)], instead of
/// interpolated from the elements around it (see final_gather.h).
///  - direct: every emitting element's exact unoccluded point-to-polygon factor times the share
///    of it that stratified shadow rays find unhidden, plus the point, spot and sun lamps at x,
///    plus the world's light at x (world.h);
///  - indirect: stratified cosine-weighted rays into the solved element radiances (or the field
///    gathered from them at the element vertices, field_rays), each hit counting its radiance less
///    its own emission (which direct has counted).
/// Deterministic: the same bake twice gives bit-identical colours.
struct FinalGatherSettings {
    bool enabled = false;
    int rays = 1024;       ///< indirect rays per corner (rounded up to a square grid)
    int shadow_rays = 64;  ///< shadow rays per corner, shared by the emitting elements it sees (at least 1 each)
    int field_rays = 0;    ///< indirect rays per element vertex, gathered first for the corners' rays to read
                           ///< (0: they read the solution interpolated, and the corners on seams keep
                           ///< no tables of the light around them: corner_wedges.h)
    /// Irradiance caching of the indirect light between output corners (irradiance_cache.h): Ward's
    /// accuracy a, the largest error measure |x - x_i| / R_i + sqrt(1 - n . n_i) at which a corner
    /// reads a gathered one's indirect light instead of gathering its own; 0: every corner gathers.
    /// Direct light stays exact at every corner.
    double cache_accuracy = 0.0;
};

}  // namespace radiosity
