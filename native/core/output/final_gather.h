/// @file final_gather.h
/// @brief The final gather at the output corners of every surface bake (internal; final_gather_settings.h).
///
/// The radiosity solution is kept for the smooth indirect light; what the artist sees at each
/// output corner is computed at the corner itself (Lischinski, Tampieri & Greenberg 1993's local
/// pass; the final gather of photon maps):
///   L(x) = L_e(x) + rho(x) [direct(x) + indirect(x)]
///  - direct(x) = sum over emitting elements j of L_e,j F_xj V_xj, with F_xj the exact unoccluded
///    point-to-polygon factor (Lambert's contour integral, near_field.h) and V_xj the share of j
///    that stratified shadow rays find unhidden (each weighted by cos cos / r^2), plus the lamps'
///    irradiance at x / pi (one shadow ray per lamp, lamp_points.h), plus the world's irradiance
///    at x / pi (world_light.h);
///  - indirect(x) = the mean, over stratified cosine-weighted rays, of the solved radiance where
///    the ray first hits an element, less that element's own emission (emission is direct's;
///    lamps' first reflection, which the solve folds into the elements' emission, is indirect
///    light and is counted). The solved radiance there is the element's interpolated corner
///    colours blended at the hit point (smooth next to seams, where the flat element value is
///    not); on an emitter's back side, which has no corner colours, its solved value. Misses and
///    back faces bring nothing (as in the hemi-cube).
/// The point x is the corner's element vertex moved a hair into its element: an input corner where
/// Cycles bakes it, 1e-4 of the vertex's largest coordinate (at least 1e-4) along its approach
/// (corner_approach.h); other vertices 1e-3 of the way to the element's centre, at most 1e-4 of the
/// scene's size. Its gather and probe rays leave x itself, as Cycles' do, and skip only faces
/// parallel to its own within 1e-6 of the scene's size (and of its largest coordinate) of its plane
/// (its own face, which round-off makes them meet: hr::Visibility::first_hit_from_surface); next to a block's foot the
/// point is only 4.5e-5 above the floor, and rays leaving 1e-6 of the scene above it read the floor 3% too bright. Its
/// shadow and World rays leave 1e-6 of the scene above it, or halfway to a surface crossing that hair
/// (hr::Visibility::lifted), so that they do not slip through the surface beside it. A point inside other geometry
/// (more than half its rays hit a back face nearer than its element's size) is moved further in (0.1 and 0.5 of the
/// way), then towards its polygon's centre (1, 2 and 4 times as far as its element's centre: the element may lie wholly
/// under what buries it, as a floor cut along a wall's footprint), so that the field and the seams, which read it, take
/// its light from the visible side. An output corner whose own point is buried (a face running on into a beam or under
/// a wall, as in game levels built from overlapping brushes) then shows what Cycles bakes at that point: its rays meet
/// back faces, which bring nothing, and its shadow rays find the lamps hidden. Every element vertex holding an input
/// corner is gathered once, so each face's corner has its own value: where a block stands on a floor, the floor's faces
/// around the block's corner see it differently (as Cycles bakes them). Where a smooth surface bends, its faces'
/// corners share their mean (replace_corners, interpolation.h). Seeds come from the vertex's position (welded), so
/// faces meeting at a vertex use the same rays and differ only where the light does, and the result does not depend on
/// threads.
///
/// The field the rays read: the solution interpolated to the elements' corners or, with
/// `field_rays`, gathered first at every element vertex with that many rays (direct light exact at
/// each vertex, indirect from the solution), so that the solution's error reaches the output only
/// after one more reflection. Elements lit by an emitter or lamp nearer to them than half their size
/// (a ceiling beside a panel hung just under it, a floor 5 cm under a lamp) keep their solved light
/// instead, their corners scaled to it: that light changes on the scale of the source's distance,
/// which their corners do not resolve. So does every later writing of gathered light into the field
/// (the output points after the first pass, the solve of the reads near them).
///
/// Bubbles (lamp_bubbles.h): a blend of corners holds only light that is linear over an element.
/// Each element of the gathered field carries a bubble (zero on its edges) that makes its mean of
/// the point lamps' light exact, so that what a surface reflects of a lamp into the rays is its whole
/// light, not its corners' blend (a floor face 90 cm under a lamp over its middle: 0.69 of it).
///
/// Wedges: where an occluder stands on a surface, the light next to the vertex turns with the
/// direction from it (the occluder's shadow starts there), and so it does along convex edges. The
/// element corners at such vertices keep a table of the light around them by direction, which the
/// rays landing in their elements read (corner_wedges.h).
///
/// Near reads: a point next to a seam (a room's edge, a block's footprint) sends half its rays into
/// the other surface right at the seam, and a wall beside a slot a centimetre wide into the slot's
/// floor, where the interpolated solution is least like the light. So the vertices on seams are
/// gathered too (those that hold no input corner with four times the field's rays: many of them are
/// read at once); the points whose rays met a surface within the size of the element hit are
/// gathered again from the first pass's values, keeping what those rays read there as weights on
/// the vertices' light, and that light is then solved (each such point's light is linear in its
/// neighbours'), as if they were gathered from each other until nothing changed.
///
/// Emitters: the emitting elements of one polygon side are one group, whose exact unoccluded light
/// at a point is one contour integral over its outline (emitter_groups.h); the group's share of the
/// shadow rays is spread over its elements by area.
///
/// Sharing (FinalGatherSettings::cache_accuracy): the indirect light of output vertices away from
/// seams, contacts and turning vertices is read from gathered neighbours with its gradients
/// (irradiance_cache.h); which vertices gather is decided from 64 probe rays' hit distances and
/// the normals, never from the light. Their direct light is gathered as everywhere.
///
/// Flat places (flat_places.h): where the faces of one flat stretch of surface meet at a vertex away
/// from seams, turning vertices and cut lines, each face has its own element vertex there, all at one
/// point with one set of seeds; the field is gathered at the first of them and the others take its
/// light (with their own reflectance), and the interpolated output points there take the first
/// interpolated one's direct light.
///
/// Cost: per output vertex, `rays` rays, its share of `shadow_rays` and a contour integral per
/// emitting run (a polygon side, or a tessellated emitter's coplanar faces); per seam vertex 4 x
/// `field_rays` rays; per element vertex (once a flat place) `field_rays`; per element corner at a
/// turning vertex, 16 direct light estimates and 4 x 4 `field_rays` rays.
#pragma once

#include "output/final_gather_settings.h"
#include "output/gather_cost.h"
#include "output/gather_hits.h"
#include "output/gather_statistics.h"
#include "output/interpolation.h"
#include "output/kept_direct_light.h"
#include "transport/lights.h"
#include "transport/world.h"

namespace radiosity::detail {

/// What earlier gathers over the same elements kept, read and added to by the next (null: nothing).
struct GatherKept {
    GatherHits* hits = nullptr;         ///< the indirect and probe rays' hits (gather_hits.h)
    KeptDirectLight* direct = nullptr;  ///< the direct light, source by source (kept_direct_light.h)
};

/// Replaces `colors` (interpolated from the solved radiance) at the output corners; counts the
/// vertices gathered, those whose indirect light was read from gathered ones, and those left
/// interpolated (a non-finite result), and each phase's seconds and rays. `emitted` is
/// each element's own emission (without the lamps' and the world's first reflection), `radiance`
/// the solved one (read flat on emitters' back sides, which have no corner colours), `world` the
/// world's light, direct at each point like the lamps'. `light_colors` (interpolated light arriving,
/// BakeResult::light_colors) takes the gathered direct + indirect light at the same corners. Progress phases "gather",
/// one unit per gathered vertex (after "gather field" with `field_rays`), then "gather near surfaces" for
/// each later pass; throws Cancelled. `statistics`, if given, takes what the gather found at the
/// output corners besides their colours (gather_statistics.h). `kept` holds what earlier gathers over
/// the same elements found: the indirect and probe rays' hits and each source's direct light at each
/// point; what is there is read instead of traced, the rest traced and kept, and the colours are the
/// same to the bit.
GatherCost final_gather(const Elements& elements, const std::vector<Rgb>& emitted, const std::vector<Rgb>& radiance,
                        const Lights& lights, const WorldLight& world, const FinalGatherSettings& settings,
                        const int32_t* material, const int32_t* face_offsets, std::size_t face_count,
                        float hard_edge_angle, CornerColors& colors, CornerColors& light_colors,
                        const ProgressFn& progress, GatherStatistics* statistics = nullptr,
                        const GatherKept& kept = {});

}  // namespace radiosity::detail
