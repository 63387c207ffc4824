/// @file media_bake.h
/// @brief The bake with participating media (internal: bake() calls it when there are media): elements, zones, exchange
/// factors, the coupled solve, corner colours and the grids a renderer needs to show the media.
///
/// Output grids per medium (zonal_grids.h): `density` = K_t and `emission` = K_t J on a lattice
/// `grid_subdivision` times finer than the voxels, J interpolated between the zones' radiances L_k
/// (at subdivision 1 without merging: K_t L_k per zone, zero outside zones). A purely absorbing
/// volume with these, as Cycles renders one (emission * tau ds along the ray), gives the zonal method's ray integral
/// along an eye ray (Rushmeier & Torrance 1987): inside zone k, int J K_t tau ds = J (tau_in - tau_out) where J is
/// constant. Where K_t differs per channel the density is RGB; Cycles' Principled Volume reaches it with colour 0,
/// density 1 and absorption colour (1 - K_t)^2 per channel while K_t <= 1, or a Volume Absorption per channel
/// otherwise.
#pragma once

#include "bake/bake.h"

namespace radiosity {

/// The surfaces as bake() returns them (solve.radiance and colors hold the elements only) and
/// the media's zones, their light and grids.
struct ZonalBakeResult : MediaResult {
    BakeResult surfaces;
};

/// bake() with media: the elements' hemi-cubes (settings.resolution) and the zones' full cubes
/// (zone_resolution) see through the media's zones (uniform blocks merged up to max_block_level),
/// made reciprocal (enforce_reciprocity); the rows are stored within settings.matrix_budget_bytes
/// (half of it for progressive refinement, which also holds R^T), else InputError. Point, spot and
/// sun lamps are shot first (lamps_in_media.h): the elements' reported emission holds their first
/// reflection and the zones' emitted radiance their first scattering, as bake() reports a first
/// reflection; `zone_incident` is the light the solve brings (R L). Progress phases "lights",
/// "form_factors", "solve"; throws Cancelled.
ZonalBakeResult bake_with_media(const SceneInput& input, const std::vector<Medium>& media, const BakeSettings& settings,
                                int zone_resolution = 32, const ProgressFn& progress = {}, int grid_subdivision = 1,
                                int max_block_level = kDefaultMaxBlockLevel);

}  // namespace radiosity
