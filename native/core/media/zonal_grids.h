/// @file zonal_grids.h
/// @brief The grids a renderer needs to show a solved medium: `density` = K_t and `emission` =
/// K_t J on a lattice `subdivision` times finer than the voxels (the zones before merging), J
/// interpolated between them (voxel_radiance spreads a merged zone over its voxels first).
///
/// A zone has one radiance L_k (its mean), but light in a medium can fall off fast across it; a
/// grid that holds L_k per zone renders steps (the fog box of docs/volumes.md was 7% off Cycles
/// at 16^3 zones). As surfaces interpolate element radiances to corners (interpolation.h), each
/// fine cell takes J trilinearly between the centres of the zones around it. Where a zone of
/// that stencil is missing (outside the medium or K_t = 0) its value is extrapolated from the
/// fine cell's own zone h along each axis a the stencil leaves h by: L_h + step_a, step_a being
/// the difference to h's neighbour on that side or, missing that, from h's neighbour on the other
/// side (the surfaces' border rule B1 + (B1 - B(e))), 0 when h has neither. J is clamped at 0,
/// then scaled per zone and channel so that its mean over the zone's fine cells is L_k: every
/// zone emits exactly the power the solve gave it, the interpolation only moves it within the
/// zone. A radiance linear in space is reproduced exactly wherever the medium is at least two
/// zones thick along each axis. K_t stays the zone's (piecewise constant).
///
/// A purely absorbing volume with these grids, as Cycles renders one (emission * tau ds along a
/// ray), gives the zonal method's ray integral (Rushmeier & Torrance 1987) with J varying inside the zones.
#pragma once

#include "media/volume.h"

#include <array>
#include <vector>

namespace radiosity {

struct MediumGrids {
    Vec3 origin{0.0f};                     ///< minimum corner, as the medium's
    float voxel_size = 0.0f;               ///< the medium's voxel size / subdivision
    std::array<int32_t, 3> dims{0, 0, 0};  ///< the medium's dims * subdivision, x fastest
    std::vector<Rgb> density;              ///< K_t per fine cell, 1/m; 0 outside zones
    std::vector<Rgb> emission;             ///< K_t J per fine cell: radiance per metre for an absorbing volume
};

/// The grids of `medium` at `subdivision` >= 1 cells per voxel edge, from `radiance`: L per voxel
/// of the medium (read only where the voxel is a zone, K_t > 0 in some channel). At subdivision 1
/// the grids are K_t and K_t L_k exactly. Throws InputError for subdivision < 1 or a radiance of
/// the wrong size.
MediumGrids medium_grids(const Medium& medium, const std::vector<Rgb>& radiance, int subdivision);

/// L per voxel of `medium` (number `medium_index` of the media `zones` were built from) for
/// medium_grids: a one-voxel zone's L_k; inside a merged block (build_zones) the linear field
/// L_k + g . (x - c_k), g per axis the difference between the mean zones just across the block's two
/// faces (one-sided with L_k at the medium's border), clamped at 0 and scaled per channel so its
/// mean over the block is L_k: each zone keeps its power. Exact for a linear radiance where the
/// zones across each face are centred on the block's axis. 0 outside zones.
std::vector<Rgb> voxel_radiance(const Medium& medium, std::size_t medium_index, const Zones& zones,
                                const std::vector<Rgb>& zone_radiance);

}  // namespace radiosity
