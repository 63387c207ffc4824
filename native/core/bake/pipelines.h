/// @file pipelines.h
/// @brief The pipelines behind bake() and the elements each solves (internal; bake.h).
#pragma once

#include "bake/bake.h"
#include "bake/kept_first_shot.h"
#include "geometry/clusters.h"
#include "output/gather_hits.h"
#include "output/kept_direct_light.h"
#include "transport/form_factors.h"

#include <memory>
#include <optional>

namespace radiosity::detail {

/// The uniform bake's elements: at most `element_size`, or the distance at which a polygon sees other
/// surfaces where that is less (visibility/sizes_by_sight.h: built once more with those sizes), cut
/// along intersections and contacts. Progress phases as build_elements'.
BuildResult uniform_elements(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress = {});

/// The uniform bake's solve elements over its output elements `build` (geometry/clusters.h): small
/// coplanar ones merged up to `element_size` (or their polygons' own sizes) when
/// BakeSettings::merge_elements, else none.
Clusters uniform_clusters(const BuildResult& build, const SceneInput& input, const BakeSettings& settings);

/// The media bake's elements: at most `element_size`, cut along intersections. The zonal exchange
/// has no direct path for lamps (small_emitters.h): their quads stay in the factors, lit and
/// blocking like any emitter (front-only still).
BuildResult media_elements(const SceneInput& input, const BakeSettings& settings);

/// Each element's light arriving, irradiance / pi, from B = E + rho H: H = (B - E) / rho per
/// channel, 0 where rho is 0 (BakeResult::light_colors). `emitted`: the elements' own emission.
std::vector<Rgb> light_arriving(const Elements& elements, const std::vector<Rgb>& radiance,
                                const std::vector<Rgb>& emitted);

/// The hierarchy's result in bake()'s shape: the leaves are the elements (the corners' colours as
/// the hierarchy made them, unless the output pass makes them).
BakeResult as_bake_result(HierarchyResult&& hierarchy);

/// The hierarchy's settings from the bake's (bake.h's HierarchicalSettings says which it takes).
HierarchySettings hierarchy_settings(const BakeSettings& settings);

/// The bytes of F over `elements` that the uniform bake plans for: matrix_bytes_bound when it fits
/// the budget (F's, or F's and F^T's for progressive refinement), else the estimate from a sample of
/// F's rows with its margin (matrix_estimate.h), rendered as the bake's settings render rows.
std::size_t planned_matrix_bytes(const Elements& elements, const BakeSettings& settings);

/// Whether F of `matrix_bytes` fits the budget (progressive refinement's: F's and F^T's).
bool fits_matrix_budget(std::size_t matrix_bytes, const BakeSettings& settings);

/// Whether the uniform bake stores F over `elements`: planned_matrix_bytes fits the budget. Stored,
/// F is computed in parallel and read cheaply by every sweep or shot, with F^T too for progressive
/// refinement's exact columns; else rows are rendered on demand (memory O(n)).
bool stores_matrix(const Elements& elements, const BakeSettings& settings);

/// What the uniform bake builds before any source shines: the elements and, within the budget, their
/// form factors, and what the final gather's rays hit. Light is linear in its sources, so one
/// transport serves every set of sources lit over it (the light groups' layers, layers.h), and a
/// BakeCache keeps it between bakes of the same geometry (bake_cache.h).
struct UniformTransport {
    BuildResult build;           ///< the output's elements; their emission is set by each light_of_sources
    std::vector<Rgb> emitted;    ///< each output element's own emission, as built from the input
    Clusters clusters;           ///< the solve's elements where small ones merged (BakeSettings::merge_elements)
    bool matrix_stored = false;  ///< F stored, else rendered on demand by each solve
    std::optional<SparseMatrix> form_factors;  ///< over the solve's elements
    /// The gather's recorded hits, read and filled by every output pass over these elements (null:
    /// each gather traces its rays).
    std::unique_ptr<GatherHits> gather_hits;
    /// The gather's direct light per source, read and added to by every output pass over these
    /// elements (null: each gather traces its shadow rays); kept by a BakeCache only.
    std::unique_ptr<KeptDirectLight> kept_direct;
    /// The lamps' first shot onto the solve's elements per lamp, read and added to by every bake over
    /// these elements (null: each traces it); kept by a BakeCache only, beside kept_direct.
    std::unique_ptr<KeptFirstShot> kept_first_shot;
    double seconds_elements = 0.0, seconds_form_factors = 0.0;

    /// The elements the form factors and the solve are over: the clusters', or the output's.
    Elements& solve_elements() { return clusters.merged() ? clusters.elements : build.elements; }
};

/// The output's elements, the solve's (merged where BakeSettings::merge_elements) and, when
/// stores_matrix, F over the solve's (progress phases as build_elements' and compute_form_factors').
UniformTransport uniform_transport(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress);

/// F over `transport`'s solve's elements when stores_matrix, else none (rendered on demand).
void solve_form_factors(UniformTransport& transport, const BakeSettings& settings, const ProgressFn& progress);

/// `transport` with `clusters` as the solve's elements (a re-bake whose lamps merge the faces
/// otherwise: cluster_elements): F over them again, and their kept first shot let go. The output's
/// elements, the gather's hits and the direct light kept at its points stay: they are the output's.
void merge_again(UniformTransport& transport, Clusters clusters, const BakeSettings& settings,
                 const ProgressFn& progress);

/// The hemi-cube rows' settings of a bake.
RowSettings row_settings(const BakeSettings& settings);

/// The light of some sources over `transport`: `emitted`, each output element's own emission (zero
/// where the sources do not emit), and the lamps and world of `settings`; lamps, world and small
/// emitters shot first, then the solve over the solve's elements, whose radiance and first
/// reflection the output's elements inherit (output/cluster_light.h), then the output pass. Fills
/// `result`'s solve, corners, solve_elements, matrix counts and the seconds of those phases (added
/// to what it holds); leaves the output elements' emission as the result reports it (own emission
/// plus the lamps' and world's first reflection).
void light_of_sources(const SceneInput& input, const BakeSettings& settings, UniformTransport& transport,
                      const std::vector<Rgb>& emitted, BakeResult& result, const ProgressFn& progress);

/// The uniform bake (see bake.h): stores F when it fits the budget, else renders rows on demand.
BakeResult bake_uniform(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress);

}  // namespace radiosity::detail
