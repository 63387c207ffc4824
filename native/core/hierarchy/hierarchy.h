/// @file hierarchy.h
/// @brief Hierarchical radiosity with clustering: elements refined where the light needs them,
/// links between groups of elements at the coarsest level that meets an error bound.
///
/// The scene's polygons are the patches. Above them sits a binary tree of clusters (a bounding
/// volume hierarchy); below them each patch splits into four elements, recursively, down to
/// `min_element_size`. Light moves along links: a receiver node gathers from a source node at
/// the coarsest pair of levels whose estimated errors, summed over the receiver's links, stay
/// below `refine_tolerance` times the scene's mean reflected radiance (Hanrahan et al. 1991, "BF
/// refinement"; clusters after Smits et al. 1994 and Sillion 1995); a receiver smaller than an
/// element of `min_element_size` may err in proportion more, by min_element_size^2 / its area
/// ("BFA" below the scale the bake resolves). The estimate is the
/// receiver's reflectance times how the transfer departs from linear over the receiver (its
/// whole spread once the receiver has children), probed at its corners and centre, times the
/// source's radiance; a partly visible pair (a shadow boundary) counts as uncertain, and so does
/// the spread of the source's own radiance where it is partly hidden or near. docs/design.md.
///
/// Factors: element to element, Lambert's contour integral from points of the receiver to the
/// source polygon (exact unoccluded, so near pairs need no special case) times the visible
/// fraction, from rays traced with Embree. A cluster is a point source whose intensity towards
/// u is max(0, M . u) + (S - |M|) / 4 with S = sum L_i A_i and M = sum L_i A_i n_i over its
/// elements: exact for one flat element and for a closed convex surface. A cluster receives
/// into six axis bins (an "ambient cube") that its elements read at their normals.
///
/// Each round solves the linked system by Jacobi sweeps with push-pull (irradiance pushed down
/// to the leaves, radiance pulled up as area means), then refines every link whose error is
/// now too large; rounds stop when no link changed and the solve has converged, or when the
/// nodes and links reached `max_bytes`.
///
/// Output: the lamps' light (point, spot, sun) is known exactly at any point, one shadow ray per
/// lamp, so each output corner shows it as it is there; after the solve, leaves split further
/// (up to `lamp_detail_levels` times) where the lamps' light inside them departs from what their
/// corners show by more than the refinement threshold: a lamp's sharp shadow gets a fine edge
/// without fine links. The light of the other links (emitting and reflecting polygons, clusters)
/// is evaluated at each corner too: each link's geometry (point-to-polygon factor, cos / r^2)
/// and, where its source was partly hidden, rays from the corner shape its mean there. What is
/// left (light pushed down from clusters, and patches smaller than `min_element_size`) is
/// interpolated from the leaves' means.
#pragma once

#include "geometry/scene.h"
#include "output/interpolation.h"
#include "transport/lights.h"
#include "transport/world.h"

#include <cstddef>
#include <memory>
#include <vector>

namespace radiosity {

struct HierarchySettings {
    float min_element_size = 0.05f;  ///< no element is split once its longest edge is below this, metres
    /// A link is refined when its estimated radiance error exceeds this times the scene's mean
    /// radiance (area-weighted). Smaller: more elements and links, a closer answer.
    double refine_tolerance = 0.02;
    double tolerance = 1e-4;             ///< relative residual of the last round's solve
    int max_iterations = 1000;           ///< Jacobi sweeps per round
    int max_rounds = 12;                 ///< refinement rounds
    float hard_edge_angle = 0.5235988f;  ///< radians, for the corner colours
    /// Cap on patches (leaves are capped by max_elements too); contact lines are cut.
    ElementLimits limits = ElementLimits().with_contacts();
    /// Cap on the bytes of nodes and links (HierarchyStats::bytes; the process peaks at about
    /// twice that): pairs stop splitting once it is reached. 0: no cap.
    std::size_t max_bytes = 0;
    Lights lights;  ///< point and spot lamps and suns: sources of links
    /// The world's light (none by default): its first reflection, the mean over each patch, joins
    /// the patch's emission for the solve; the output's corners show it as it is at each corner
    /// (WorldLight::point_samples rays per corner), with the patch's mean taken out of the rest.
    WorldLight world;
    /// Leaves may split this many levels below `min_element_size` after the solve where the
    /// lamps' light needs it (along their shadows' edges): the finest are min_element_size / 2^this.
    int lamp_detail_levels = 2;
    /// The output's corners are left to a final gather (output/final_gather.h), which takes each
    /// corner's direct light at the corner and reads the leaves' radiance for the indirect light:
    /// no lamp detail, no corner colours here (HierarchyResult::colors stay empty).
    bool gathered_output = false;
};

struct HierarchyStats {
    std::size_t patches = 0, clusters = 0, leaves = 0, nodes = 0, links = 0, rays = 0;
    std::size_t bytes = 0;        ///< nodes and links held at the end (the bulk of the memory)
    std::size_t lamp_splits = 0;  ///< leaves split after the solve for the lamps' light
    int rounds = 0, iterations = 0;
    bool leaf_cap_reached = false;    ///< refinement stopped early at ElementLimits::max_elements
    bool memory_cap_reached = false;  ///< refinement stopped early at HierarchySettings::max_bytes
};

struct HierarchyResult {
    BuildResult build;  ///< the patches (one element per polygon or n-gon piece)
    /// Output mesh: the leaves, with every hanging vertex of a finer neighbour on their edges
    /// (leaves that have one are split into triangles and quads with those vertices as corners),
    /// so the colours have no cracks.
    Elements output;                   ///< emission: E + rho G from the lamps (their first reflection)
    std::vector<Rgb> output_radiance;  ///< per output element: its leaf's radiance
    std::vector<Rgb> output_emitted;   ///< per output element: its own emission (no lamp's or world's reflection)
    CornerColors colors;        ///< interpolated on the output mesh; input corners for ORIGINAL (not gathered_output)
    CornerColors light_colors;  ///< the light arriving at the same corners, irradiance / pi (not gathered_output)
    HierarchyStats stats;
    double residual = 0.0;
    bool converged = false;
    std::vector<double> residual_history;
    double seconds_elements = 0, seconds_links = 0, seconds_solve = 0, seconds_interpolate = 0;
};

/// The patches bake_hierarchical() starts from: one element per polygon (n-gons: convex pieces),
/// cut along intersection and contact lines; lamps' quads block light like any patch.
/// Throws InputError for settings out of range, as bake_hierarchical() does.
BuildResult hierarchy_patches(const SceneInput& input, const HierarchySettings& settings);

/// Which of a scene's sources shine (RefinedHierarchy::light): per input polygon (its emission), per
/// point or spot lamp, per sun, and the World.
struct SourceMask {
    std::vector<uint8_t> polygon, point, sun;
    bool world = false;
};

/// A hierarchical bake up to its output: patches, tree and links, refined for all of the scene's
/// sources. It can then make the bake's output, or be lit again by some of the sources over the same
/// links and leaves (light group layers, bake/layers.h), as often as asked. Keeps references to the
/// input and settings, which must outlive it.
class RefinedHierarchy {
public:
    /// Builds and refines as bake_hierarchical() does (its progress phases and errors).
    RefinedHierarchy(const SceneInput& input, const HierarchySettings& settings, const ProgressFn& progress = {});
    ~RefinedHierarchy();
    RefinedHierarchy(const RefinedHierarchy&) = delete;
    RefinedHierarchy& operator=(const RefinedHierarchy&) = delete;

    /// What the refinement made: the patches (build), its rounds and sweeps, seconds of elements,
    /// links and solve.
    const HierarchyResult& refinement() const;
    /// bake_hierarchical()'s result (frees the links: the last call).
    HierarchyResult output(const ProgressFn& progress = {}) &&;
    /// The leaves lit by the sources `on` alone: the links solved again from their emission, lamps
    /// and World (the refinement is the one for all sources); output, its radiance and own emission,
    /// the solve's statistics (gathered_output only: the output pass gathers its corners). `build` is
    /// left empty (refinement()). Progress phases "solve" and "output".
    HierarchyResult light(const SourceMask& on, const ProgressFn& progress = {});

    struct State;

private:
    std::unique_ptr<State> state_;
};

/// Bakes `input` hierarchically. Progress phases "elements" (set-up), "links" (refinement, per
/// round), "solve" and "output" (the leaf mesh);
/// throws Cancelled, InputError (as build_elements, or when the leaves would pass the cap).
HierarchyResult bake_hierarchical(const SceneInput& input, const HierarchySettings& settings,
                                  const ProgressFn& progress = {});

}  // namespace radiosity
