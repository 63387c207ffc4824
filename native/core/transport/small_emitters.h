/// @file small_emitters.h
/// @brief Emitting elements too small for the hemi-cube, lit directly at the receiving elements
/// (internal; bake.h's BakeSettings::direct_emitter_area).
///
/// A hemi-cube sees an emitter a few cells wide as a blotch: its factors alias by tens of percent
/// and the light it casts comes out patchy, unless the resolution grows as 1 / sqrt(area) for the
/// whole bake (a 1 cm lamp in a 2 m room asks for 850). Instead, each small emitting element j
/// lights each element i directly, as a source with its true area and shape (the shooting step of
/// progressive refinement with analytic factors, Wallace, Elmquist & Haines 1989):
///   incoming_i = sum_j L_j (A_i F_ij) V_ij / A_i,
///  - A_i F_ij: area_flux (near_field.h), point-to-polygon factors from Gauss-Legendre points of
///    the smaller element to the larger, so exact over the receiver when the emitter is smaller;
///  - V_ij: the share of stratified rays between points of j and of i that nothing hides, each
///    weighted by cos cos / r^2.
/// Cost: emitters x elements pairs (most culled by their planes), so only small emitters take
/// this path; the caller bounds their number.
#pragma once

#include "common/types.h"
#include "geometry/scene.h"

#include <vector>

namespace radiosity::detail {

/// Each element's incoming radiance (irradiance / pi) from the emitting elements `emitters`, each
/// at its emission `emitted`. Progress phase "small emitters", one unit per element; throws Cancelled.
std::vector<Rgb> small_emitter_light(const Elements& elements, const std::vector<int32_t>& emitters,
                                     const std::vector<Rgb>& emitted, const ProgressFn& progress);

}  // namespace radiosity::detail
