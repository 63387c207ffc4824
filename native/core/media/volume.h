/// @file volume.h
/// @brief Participating media on regular voxel grids, the zones they are split into, and the
/// coefficients Cycles' Principled Volume gives them.
///
/// The zonal method (seed 002, Rushmeier & Torrance 1987) treats every voxel with extinction
/// K_t > 0 as a zone: a uniform, isotropic emitter and scatterer. Empty voxels are not zones:
/// they cost nothing but a step of the ray walk (transmittance.h). Where neighbouring voxels have
/// the same coefficients, build_zones can merge them into octree blocks (one zone each), as
/// hierarchical radiosity clusters uniform regions: exchange factors cost zones squared.
///
/// Units (radiance, as the surface system): a voxel's `emission` is Cycles' volume emission,
/// radiance added per metre of path (dL/ds = -K_t L + emission + sigma_s L_in). A zone's
/// radiance J_k is the zone radiosity B_k / pi of Rushmeier & Torrance 1987, the radiance it sends out by emission and
/// scattering:
///   J_k = emission_k / K_t,k + Omega_k * (incident radiance, mean over the zone and all directions),
/// which is their zone equation divided by 4 pi K_t V_k: (1 - Omega) E = K_a E / K_t with
/// K_a E the emission coefficient. So `Zones::emitted` = emission / K_t plays the role of a
/// surface's emitted radiance and Omega that of its reflectance.
#pragma once

#include "common/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace radiosity {

/// Absorption, scattering and emission coefficients of a medium at a point (per RGB channel).
struct VolumeCoefficients {
    Rgb scattering{0.0};                                        ///< sigma_s, 1/m
    Rgb absorption{0.0};                                        ///< sigma_a, 1/m
    Rgb emission{0.0};                                          ///< radiance per metre of path
    Rgb extinction() const { return scattering + absorption; }  ///< K_t = sigma_s + sigma_a
};

/// The Principled Volume as Cycles evaluates it (svm_node_principled_volume in
/// intern/cycles/kernel/svm/closure.h, unchanged from Blender 2.8 to 4.x), blackbody excluded:
///   sigma_s = density * color
///   sigma_a = density * max(1 - color, 0) * max(1 - sqrt(absorption_color), 0)
///   emission = emission_strength * emission_color
/// Note the square root on the absorption colour. `density` includes the density attribute.
/// Negative density counts as 0, as in Cycles.
VolumeCoefficients principled_volume(const Rgb& color, double density, const Rgb& absorption_color,
                                     double emission_strength, const Rgb& emission_color);

/// A medium on a regular grid of cubic voxels. Voxel (x, y, z) covers
/// origin + voxel_size * [x, x+1] x [y, y+1] x [z, z+1]; arrays are indexed x + dims[0] * (y + dims[1] * z).
struct Medium {
    Vec3 origin{0.0f};        ///< world position of the grid's minimum corner, metres
    float voxel_size = 0.0f;  ///< voxel edge, metres
    std::array<int32_t, 3> dims{0, 0, 0};
    std::vector<Rgb> extinction;  ///< K_t per voxel, 1/m, >= 0
    std::vector<Rgb> albedo;      ///< Omega = sigma_s / K_t per voxel, in [0, 1]
    std::vector<Rgb> emission;    ///< radiance per metre per voxel, >= 0; 0 where K_t = 0

    /// An empty (all zero) grid of the given shape.
    Medium(const Vec3& origin, float voxel_size, const std::array<int32_t, 3>& dims);
    Medium() = default;

    std::size_t voxel_count() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
    std::size_t index(int32_t x, int32_t y, int32_t z) const {
        return x + std::size_t(dims[0]) * (y + std::size_t(dims[1]) * z);
    }
    /// Sets a voxel from coefficients: K_t, Omega = sigma_s / K_t (0 where K_t = 0), emission.
    void set(std::size_t voxel, const VolumeCoefficients& c);
};

/// The zones of all media, medium by medium: cubes of block^3 voxels with K_t > 0 in some channel.
struct Zones {
    std::vector<int32_t> medium;  ///< index into the media
    std::vector<int32_t> voxel;   ///< linear index of the block's minimum-corner voxel in its medium
    std::vector<int32_t> block;   ///< voxels per edge: 1, or 2^level for a merged octree block
    std::vector<Vec3> centre;     ///< world space
    std::vector<float> edge;      ///< block edge, metres
    std::vector<Rgb> extinction;  ///< K_t, 1/m
    std::vector<Rgb> albedo;      ///< Omega
    std::vector<Rgb> emitted;     ///< emission / K_t: the radiance the zone emits (0 where K_t = 0)

    std::size_t size() const { return voxel.size(); }
    double volume(std::size_t k) const { return double(edge[k]) * edge[k] * edge[k]; }
    /// 4 K_t V: the zone's outgoing power per unit radiance, over pi (a surface's is its area).
    Rgb weight(std::size_t k) const { return 4.0 * extinction[k] * volume(k); }
};

/// Two voxels merge when every coefficient (K_t, Omega, emission; each channel) agrees to this
/// relative difference. Exact equality would split a uniform fog at random: the add-on's float32
/// grids carry rounding of a few 1e-7 from box-averaged voxelisation. 1e-5 is far above that and
/// moves a transmittance exp(-K s) by at most 1e-5 of the optical depth, 10x below the default
/// solve tolerance (1e-4). A merged zone takes the block's means (total K_t, scattering and
/// emission kept).
constexpr double kUniformTolerance = 1e-5;

/// Collects the zones of `media`. With max_block_level > 0, aligned blocks of 2^l voxels per edge
/// (l = max_block_level down to 1, blocks at multiples of 2^l inside the grid) whose voxels are all
/// zones of equal coefficients (kUniformTolerance) become one zone each; 0 keeps one zone per voxel,
/// x fastest. Throws InputError (naming medium and voxel) for non-finite or
/// negative values, albedo outside [0, 1], emission where K_t = 0 (it could not be absorbed, so the
/// zonal system cannot hold it), array sizes that do not match dims, and media whose occupied
/// boxes overlap (merge overlapping media into one grid).
Zones build_zones(const std::vector<Medium>& media, int max_block_level = 0);

/// Per voxel of `medium` (number `medium_index` of the media `zones` came from): its zone, -1 where empty.
std::vector<int32_t> voxel_zones(const Medium& medium, std::size_t medium_index, const Zones& zones);

}  // namespace radiosity
