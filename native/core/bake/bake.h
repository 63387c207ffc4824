/// @file bake.h
/// @brief The bake, whatever the method and with or without media: plan() says what it will solve,
/// bake() solves it and returns one result shape.
///
/// Three pipelines sit behind bake(), chosen by the settings:
///  - uniform (the default; uniform_bake.h): elements of at most `element_size`, hemi-cube form
///    factors, Gauss-Seidel, Jacobi or progressive refinement, interpolation, the final gather;
///  - hierarchical (`hierarchical.enabled`; hierarchy/hierarchy.h): elements refined where the
///    light needs them, down to `element_size`, clusters linked far off, visibility by rays;
///  - with media (`media.media` not empty; media_bake.h): the uniform elements and the media's
///    zones in one zonal system.
/// `element_size` means the same in each: the longest edge of the finest elements the bake
/// resolves (uniform: every element; hierarchical: where refinement stops).
///
/// In the uniform and media bakes, which system is solved depends on whether F fits `matrix_budget_bytes`:
///  - stored (the budget holds F; progressive refinement needs F and F^T, twice that): every
///    method solves L = E + rho F L exactly; progressive refinement shoots columns of F.
///  - on demand (beyond the budget): rows are rendered one hemi-cube at a time, memory O(n).
///    Gauss-Seidel and Jacobi still solve with F, at one hemi-cube per element per sweep (serial,
///    so slow: Jacobi needs about twice Gauss-Seidel's sweeps). Progressive refinement shoots by
///    reciprocity and solves with G_ji = F_ij A_i / A_j instead (see solver.h): a known deviation
///    of up to some percent next to shared edges, e.g. in a closed box furnace.
#pragma once

#include "hierarchy/hierarchy.h"
#include "media/volume.h"
#include "media/zonal.h"
#include "media/zonal_grids.h"
#include "output/final_gather_settings.h"
#include "output/gather_cost.h"
#include "output/gather_statistics.h"
#include "output/interpolation.h"
#include "solve/solver.h"
#include "transport/lights.h"
#include "transport/world.h"

#include <optional>
#include <string>
#include <vector>

namespace radiosity {

class BakeCache;

/// Hierarchical radiosity instead of uniform elements (hierarchy/hierarchy.h). It takes
/// BakeSettings' element_size (the finest elements, > 0), solve tolerance and sweeps, hard edge
/// angle, element limits, lamps and world; no hemi-cube, so no resolution, near field or gather.
struct HierarchicalSettings {
    bool enabled = false;
    double refine_tolerance = HierarchySettings().refine_tolerance;  ///< error per link, share of the mean radiance
    std::size_t max_bytes = 0;                                       ///< cap on the nodes' and links' bytes (0: none)
};

/// Uniform regions of a medium merge into octree blocks of up to 2^this voxels per edge
/// (build_zones): the exchange factors cost zones squared. 0 keeps one zone per voxel.
constexpr int kDefaultMaxBlockLevel = 1;

/// Participating media solved with the surfaces by the zonal method (media_bake.h).
struct MediaSettings {
    std::vector<Medium> media;  ///< none: a surface bake
    int zone_resolution = 32;   ///< the zones' full cubes: cells per face edge (even, >= 8)
    int grid_subdivision = 3;   ///< output grid cells per voxel edge
    int max_block_level = kDefaultMaxBlockLevel;
};

struct BakeSettings {
    /// The longest edge of the finest elements, metres (see the top of this file); 0 = one element
    /// per polygon (uniform and media bakes only).
    float element_size = 0.0f;
    int resolution = 128;  ///< hemi-cube cells per full face edge
    SolveSettings solve;
    float hard_edge_angle = 0.5235988f;  ///< radians (30 degrees)
    /// Element cap, sliver split, intersection and contact cuts (docs/stability.md).
    ElementLimits limits = ElementLimits().with_contacts();
    /// Uniform bakes: the solve's elements are chosen by the element size, not the faces: small
    /// coplanar elements of one surface merge into convex ones of up to `element_size`, whose light
    /// the output's elements inherit (geometry/clusters.h). false: one unknown per output element.
    bool merge_elements = true;
    /// Hemi-cubes per row at turned orientations, averaged (aliasing of small or distant
    /// elements; see RowSettings::rotations). 1 = a single hemi-cube (Cohen & Greenberg 1985).
    int hemicube_rotations = 1;
    /// Analytic factors for near pairs (shared edges, receivers closer than their size); off by default.
    NearFieldSettings near_field;
    /// Memory allowed for the stored matrix, judged by matrix_bytes_bound, or where that passes it
    /// by an estimate from a sample of the matrix's rows (matrix_estimate.h); 2 GiB by default.
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
    /// Hierarchical radiosity instead of uniform elements (off by default).
    HierarchicalSettings hierarchical;
    /// Media solved with the surfaces (none by default).
    MediaSettings media;
};

/// What a bake with media adds: the zones and their light, and the grids a renderer shows.
struct MediaResult {
    Zones zones;                     ///< after merging; zones.block[k]^3 voxels each
    std::vector<Rgb> zone_radiance;  ///< L_k per zone
    /// H_k = sum_y R_ky L_y: the mean radiance a zone receives, so a caller can count the power it
    /// absorbs, pi (4 K_t V) (1 - Omega) H_k (its radiance alone cannot say when Omega = 0).
    std::vector<Rgb> zone_incident;
    std::vector<MediumGrids> grids;  ///< per medium, at MediaSettings::grid_subdivision
    double seconds_zones = 0.0;
};

/// Whether a bake given a BakeCache read what the previous bake learned about the geometry, and
/// whether the cache keeps what this one learned (bake_cache.h).
struct CacheUse {
    bool reused = false;           ///< the elements, form factors and the gather's hits of the previous bake
    bool kept = false;             ///< the cache holds this bake's for the next
    std::size_t bytes = 0;         ///< what the cache holds after the bake (0 when not kept)
    std::string not_reused;        ///< why it was not reused ("" when it was)
    std::string not_kept;          ///< why it was not kept ("" when it was)
    std::size_t direct_bytes = 0;  ///< of `bytes`, the direct light kept per source (gather, first shot)
    bool merged_again = false;     ///< reused, but its lamps merge the faces otherwise: F computed anew
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
    /// The hierarchy's adds, at each corner, the light its lamps, World and links bring there.
    CornerColors light_colors;
    /// The unknowns solved: the uniform bake's merged elements (geometry/clusters.h), else build's.
    std::size_t solve_elements = 0;
    bool matrix_stored = false;       ///< F stored (exact system) or rows rendered on demand
    std::size_t matrix_nonzeros = 0;  ///< 0 when rows were rendered on demand
    std::size_t matrix_bytes = 0;     ///< matrices held at once (progressive: F and F^T)
    double seconds_elements = 0, seconds_lights = 0, seconds_form_factors = 0, seconds_solve = 0,
           seconds_interpolate = 0;
    double seconds_world = 0;             ///< the world's light on the elements (0 without a world)
    double seconds_gather = 0;            ///< the final gather (0 when off)
    std::size_t gathered_points = 0;      ///< output vertices the final gather gathered with their own rays
    std::size_t interpolated_points = 0;  ///< output vertices whose indirect light it read from gathered ones
    std::size_t buried_points = 0;        ///< gathered light not finite: interpolated colour kept
    GatherCost gather_cost;               ///< the final gather's phases: seconds and rays (gather_cost.h)
    /// What the final gather found at the output corners besides their colours (with the gather).
    std::optional<GatherStatistics> gather_statistics;
    std::size_t direct_emitters = 0;     ///< emitting elements lit directly (direct_emitter_area)
    double seconds_direct_emitters = 0;  ///< their direct light on every element
    /// Hierarchical bakes: the tree's counts. `build` is then the output mesh (the leaves), `solve`
    /// its radiance, and the form factors' seconds are the links'.
    std::optional<HierarchyStats> hierarchy;
    std::optional<MediaResult> media;  ///< bakes with media; `build` and `solve` hold the surfaces
    std::optional<CacheUse> cache;     ///< bakes given a BakeCache
};

/// What bake() will solve, before it solves: the same elements, and for the uniform methods the
/// form factors' memory bound and whether they are stored (else rendered on demand).
struct BakePlan {
    /// The elements as bake() builds them (with the same cuts); the hierarchy's are its patches,
    /// one a polygon, which it refines.
    BuildResult build;
    std::size_t solve_elements = 0;  ///< the unknowns: uniform bakes' merged elements (else build's elements)
    /// The unknowns' areas, square metres: what the hemi-cube's resolution must resolve (the
    /// uniform bake's merged elements; else build's elements').
    std::vector<float> solve_element_area;
    std::vector<int32_t> solve_element_polygon;  ///< the input polygon each unknown came from (a merged one's first)
    std::size_t matrix_bytes_bound = 0;          ///< uniform and media bakes: matrix_bytes_bound at settings.resolution
    /// Uniform bakes: the bound when it fits the budget, else the stored matrix's bytes estimated
    /// from a sample of its rows at settings' resolution, rotations and near field, with a margin
    /// (matrix_estimate.h); media bakes: the bound.
    std::size_t matrix_bytes_planned = 0;
    bool matrix_stored = false;  ///< uniform bakes: matrix_bytes_planned fits the budget (media bakes always store)
    /// The distance at which the elements see each other (sight_distance.h), and the one the
    /// hemi-cube's resolution is judged from (resolution_distance, resolution.h): 1.9 times that, at
    /// most half the diagonal of the elements' bounding box.
    double sight_distance = 0.0, resolution_distance = 0.0;
};

/// Upper bound of F's memory: n rows of at most min(n, 3 N^2) nonzeros (the hemi-cube's cells at
/// resolution N: N^2 on top, four sides of N^2 / 2), 8 bytes each (float value, int32 column).
std::size_t matrix_bytes_bound(std::size_t element_count, int resolution);

/// The elements, memory bound and storage bake() will use with the same input and settings.
/// Throws InputError as bake() would for the input and the settings it checks.
BakePlan plan(const SceneInput& input, const BakeSettings& settings);

/// Bakes by the pipeline the settings choose (see the top of this file). Progress phases and
/// errors as each pipeline's; throws Cancelled. With `cache`, a uniform bake reuses what the cache's
/// previous bake learned about the same geometry and leaves its own there (bake_cache.h); other
/// methods empty it.
BakeResult bake(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress = {},
                BakeCache* cache = nullptr);

}  // namespace radiosity
