/// @file bake.h
/// @brief The whole surface bake: elements, form factors, solve, corner colours.
///
/// Which system is solved depends on whether F fits `matrix_budget_bytes`:
///  - stored (the budget holds F; progressive refinement needs F and F^T, twice that): every
///    method solves L = E + rho F L exactly; progressive refinement shoots columns of F.
///  - on demand (beyond the budget): rows are rendered one hemi-cube at a time, memory O(n).
///    Gauss-Seidel and Jacobi still solve with F, at one hemi-cube per element per sweep (serial,
///    so slow: Jacobi needs about twice Gauss-Seidel's sweeps). Progressive refinement shoots by
///    reciprocity and solves with G_ji = F_ij A_i / A_j instead (see solver.h): a known deviation
///    of up to some percent next to shared edges, e.g. in a closed box furnace.
#pragma once

#include "radiosity/interpolation.h"
#include "radiosity/lights.h"
#include "radiosity/solver.h"
#include "radiosity/world.h"

namespace radiosity {

/// A final gather at the output corners (off by default): each input corner's radiance is computed
/// at the corner itself, L(x) = L_e(x) + rho(x) [direct(x) + indirect(x)], instead of
/// interpolated from the elements around it (see final_gather.h).
///  - direct: every emitting element's exact unoccluded point-to-polygon factor times the share
///    of it that stratified shadow rays find unhidden, plus the point, spot and sun lamps at x,
///    plus the world's light at x (world.h);
///  - indirect: stratified cosine-weighted rays into the solved element radiances, each hit
///    counting its radiance less its own emission (which direct has counted).
/// Deterministic: the same bake twice gives bit-identical colours.
struct FinalGatherSettings {
    bool enabled = false;
    int rays = 1024;         ///< indirect rays per corner (rounded up to a square grid)
    int shadow_rays = 64;    ///< shadow rays per corner, shared by the emitting elements it sees (at least 1 each)
};

struct BakeSettings {
    float element_size = 0.0f;       ///< max element edge in metres, 0 = one element per polygon
    int resolution = 128;            ///< hemi-cube cells per full face edge
    SolveSettings solve;
    float hard_edge_angle = 0.5236f; ///< radians (30 degrees)
    /// Element cap, sliver split, intersection and contact cuts (docs/stability.md).
    ElementLimits limits = ElementLimits().with_contacts();
    /// Hemi-cubes per row at turned orientations, averaged (aliasing of small or distant
    /// elements; see RowSettings::rotations). 1 = the seed's single hemi-cube.
    int hemicube_rotations = 1;
    /// Analytic factors for near pairs (shared edges, receivers closer than their size); off by default.
    NearFieldSettings near_field;
    /// Memory allowed for the stored matrix, judged by matrix_bytes_bound (2 GiB by default).
    std::size_t matrix_budget_bytes = std::size_t(2) << 30;
    /// Point, spot and sun lamps, shot once before the solve: each element's reflected direct
    /// light rho E / pi joins its emitted radiance.
    Lights lights;
    /// The world's light (an environment map; none by default), received like the lamps': each
    /// element's rho E / pi joins its emitted radiance, and the final gather adds it at each point.
    WorldLight world;
    /// The final gather at the output corners (off by default).
    FinalGatherSettings final_gather;
    /// Emitting elements smaller than this (square metres; 0 = none) light every element directly,
    /// as sources with their true area and shape, instead of through the hemi-cube, which would
    /// need a resolution that resolves them (small_emitters.h). Their own emission is left out of
    /// the solve and added back to their radiance after it.
    float direct_emitter_area = 0.0f;
};

struct BakeResult {
    BuildResult build;
    SolveResult solve;
    /// The colours written. A textured face's corners show the texel at the corner times the light
    /// arriving there (light_colors), plus its emission texture's texel (texture.h).
    CornerColors colors;
    /// The light arriving at the same corners without the surface's colour, irradiance / pi (as
    /// Cycles' Diffuse bake with Direct and Indirect and without Color): for a surface that does
    /// not emit, light x reflectance = colors. Without the final gather it is interpolated from
    /// each element's (radiance - own emission) / reflectance, and is 0 in a channel whose
    /// reflectance is 0 (such a surface reflects nothing there, whatever light arrives); with the
    /// gather, the gathered output corners hold the light the gather found, whatever the colour.
    CornerColors light_colors;
    bool matrix_stored = false;        ///< F stored (exact system) or rows rendered on demand
    std::size_t matrix_nonzeros = 0;   ///< 0 when rows were rendered on demand
    std::size_t matrix_bytes = 0;      ///< matrices held at once (progressive: F and F^T)
    double seconds_elements = 0, seconds_lights = 0, seconds_form_factors = 0, seconds_solve = 0, seconds_interpolate = 0;
    double seconds_world = 0;           ///< the world's light on the elements (0 without a world)
    double seconds_gather = 0;          ///< the final gather (0 when off)
    std::size_t gathered_points = 0;    ///< output vertices whose colour the final gather computed
    std::size_t buried_points = 0;      ///< output vertices inside other geometry: interpolated colour kept
    std::size_t direct_emitters = 0;    ///< emitting elements lit directly (direct_emitter_area)
    double seconds_direct_emitters = 0; ///< their direct light on every element
};

/// Upper bound of F's memory: n rows of at most min(n, 3 N^2) nonzeros (the hemi-cube's cells at
/// resolution N: N^2 on top, four sides of N^2 / 2), 8 bytes each (float value, int32 column).
std::size_t matrix_bytes_bound(std::size_t element_count, int resolution);

/// Stores F when it fits the budget, else renders rows on demand (see the top of this file).
BakeResult bake(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress = {});

}  // namespace radiosity
