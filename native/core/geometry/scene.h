/// @file scene.h
/// @brief Scene input as flat arrays, and its subdivision into elements (the unknowns).
#pragma once

#include "common/types.h"
#include "geometry/texture.h"

#include <array>
#include <cstdint>
#include <vector>

namespace radiosity {

/// A polygon soup as flat arrays (views; the caller owns the memory). Units: metres, world space.
/// Polygon f has corners corner_vertices[face_offsets[f] .. face_offsets[f+1]), counter-clockwise
/// seen from the side its normal points to (Blender's convention).
struct SceneInput {
    const float* positions = nullptr;  ///< vertex_count x 3
    std::size_t vertex_count = 0;
    const int32_t* face_offsets = nullptr;     ///< face_count + 1, starts at 0, increasing
    const int32_t* corner_vertices = nullptr;  ///< face_offsets[face_count] vertex indices
    std::size_t face_count = 0;
    const float* reflectance = nullptr;  ///< face_count x 3, each in [0, 1)
    const float* emission = nullptr;     ///< face_count x 3, emitted radiance, >= 0
    const int32_t* material = nullptr;   ///< face_count ids; corners never blend across ids. May be null.
    /// face_count flags: an emitting face that emits from its front only, as Cycles' area lamps do
    /// (other emitting faces emit from both sides, Elements::side). May be null: none.
    const uint8_t* front_only = nullptr;
    /// face_count flags: a face whose back side looks into the scene (visibility/open_backs.h). In
    /// Cycles every face reflects from both sides; such a face does here too (Elements::side). May be
    /// null: none.
    const uint8_t* open_back = nullptr;
    /// Image textures that vary the faces' reflectance and emission about their mean (texture.h).
    /// May be null: every face is its flat colour.
    const SurfaceTextures* textures = nullptr;
};

/// The unknowns of the radiosity system: small planar triangles or quads, each a uniform
/// emitter and reflector. Elements of one polygon share their grid vertices.
struct Elements {
    std::vector<Vec3> vertices;                   ///< element grid vertices, world space
    std::vector<std::array<int32_t, 4>> corners;  ///< indices into vertices, CCW; [3] == -1 for a triangle
    std::vector<Vec3> centre;                     ///< centroid (hemi-cubes sit here)
    std::vector<Vec3> normal;                     ///< unit normal
    std::vector<float> area;                      ///< square metres
    std::vector<int32_t> polygon;                 ///< input polygon each element came from (cut pieces too)
    std::vector<Rgb> reflectance;                 ///< per element, in [0, 1)
    std::vector<Rgb> emission;                    ///< emitted radiance per element
    /// Bit k: the edge from corner k to corner k + 1 lies where another polygon passes through this
    /// element's polygon; corner colours do not blend across it. Empty = no such edges.
    std::vector<uint8_t> cut_edges;
    /// Emitting polygons are two-sided, as in Cycles, where a face with an emissive material emits
    /// (and reflects) from both sides, and so are the faces whose back looks into the scene
    /// (SceneInput::open_back), which reflect from both sides: build_elements gives each of their
    /// elements a back side, a twin on the same vertices with its corners reversed (normal, centre,
    /// area, polygon, reflectance and emission as the front's, normal negated), appended after all
    /// the fronts.
    /// Per element: kOneSided, kFront (of such a pair) or kBack. The twins never hide each other:
    /// an element that has a twin, seen from behind, is left to its twin (hemi-cube, sun raster).
    /// A back side is solved like any element but its colours are not written (the mesh shows its
    /// front, as Blender draws it): interpolation skips it. Empty = every element one-sided.
    std::vector<uint8_t> side;
    static constexpr uint8_t kOneSided = 0, kFront = 1, kBack = 2;

    /// Input corner -> element vertex holding the polygon's corner (for writing back colours);
    /// -1 for corners of skipped (degenerate) polygons.
    std::vector<int32_t> corner_vertex;

    std::size_t size() const { return centre.size(); }
    /// Per element: 1 for a lamp's (an emitting face marked front only, SceneInput::front_only):
    /// as in Cycles it emits but blocks no light, so hemi-cubes and rays pass through it and its
    /// light reaches the other elements directly (small_emitters.h). Empty: no lamps.
    std::vector<uint8_t> lamp;
    bool blocks(std::size_t e) const { return lamp.empty() || !lamp[e]; }
    int corner_count(std::size_t e) const { return is_triangle(e) ? 3 : 4; }
    bool is_triangle(std::size_t e) const { return corners[e][3] < 0; }
    /// Whether element e is one of a front and back pair (see `side`).
    bool has_twin(std::size_t e) const { return !side.empty() && side[e] != kOneSided; }
    /// Whether element e is the back side of a two-sided polygon (see `side`).
    bool is_back(std::size_t e) const { return !side.empty() && side[e] == kBack; }
};

/// Why a polygon was left out.
enum class Defect : int32_t { ZeroArea = 1, NonFinite = 2, TooFewCorners = 3, BadIndex = 4 };

struct SkippedPolygon {
    int32_t polygon;
    Defect defect;
};

/// Colours at the corners of the elements and of the input polygons: what a bake writes
/// (output/interpolation.h fills them from the elements' radiance).
struct CornerColors {
    /// Per corner of each element (4 per element; the 4th unused for triangles).
    std::vector<Rgb> element_corner;
    /// Per input corner (SceneInput's corner order); zero for skipped polygons.
    std::vector<Rgb> input_corner;
};

struct BuildResult {
    Elements elements;
    std::vector<SkippedPolygon> skipped;  ///< never used silently: callers report these
    /// Per input polygon, the longest edge it was cut to where smaller than the bake's element size
    /// (ElementLimits::polygon_edge; 0 elsewhere, empty: none).
    std::vector<float> polygon_edge;
};

/// Guards of the subdivision against input it cannot serve.
struct ElementLimits {
    /// More elements than this is an InputError naming the polygon that crosses the cap, raised
    /// before any element is made (a 1e6 m floor at 1 cm would be 1e16 elements). 2^21 elements
    /// take about 250 MB here, and a bake of that many takes hours; real scenes need far fewer.
    std::size_t max_elements = std::size_t(1) << 21;
    /// Thin slivers (docs/stability.md), 0 = off. Convex quads: cut the long direction further
    /// until no element is longer than `max_aspect` times its width. Triangles longer than
    /// `max_aspect` times their height: cut into strips across their length, from the corner
    /// opposite a short edge, or from both ends of the longest edge to the altitude's foot.
    /// Bounded by size, not aspect: no piece is cut shorter than 1/32 of the element size, nor
    /// to less area than (element size / 32)^2 (a face of negligible area carries negligible light).
    float max_aspect = 0.0f;
    /// The element size those bounds take where build_elements' max_edge is 0 (the hierarchy's
    /// patches, which it refines down to its own element size). 0: each polygon's longest edge,
    /// and no area bound.
    float element_size = 0.0f;
    /// Cut polygons along the lines where other polygons pass through them, before subdividing, so
    /// that no element straddles an intersection and leaks light across it (docs/stability.md).
    bool cut_intersections = true;
    /// With cut_intersections: cut them along contact lines too, where another polygon stands on
    /// them (a box on a floor), so no element straddles the footprint's outline; and along the
    /// outline of an emitting polygon hung close in front of them (parallel, within a tenth of its
    /// longest edge, its back side towards them: a panel under a ceiling), so no element straddles
    /// the edge of the light its back side casts. Off here, on in the uniform and hierarchical
    /// bakes (BakeSettings::limits, HierarchySettings::limits).
    bool cut_contacts = false;
    /// Per input polygon, a longest edge below build_elements' max_edge for its elements (0: max_edge
    /// alone; visibility/sizes_by_sight.h). Empty: none.
    std::vector<float> polygon_edge;

    /// These limits with contact cuts on.
    ElementLimits with_contacts() const {
        ElementLimits limits = *this;
        limits.cut_contacts = true;
        return limits;
    }
};

/// Splits every polygon into elements whose edges are at most `max_edge` metres long
/// (0 = one element per polygon; n-gons are always split into triangles and quads), after cutting
/// it along the lines where other polygons pass through it (`limits.cut_intersections`). Every
/// element of an emitting polygon (emission > 0 in any channel) and of a polygon with an open back
/// (SceneInput::open_back) gets a back side (Elements::side), after all the polygons' elements.
/// Textured faces (SceneInput::textures) give their elements their mean colour over the element.
/// Throws InputError for arrays that are inconsistent as a whole (offsets out of order,
/// reflectance outside [0, 1), negative or non-finite emission) or beyond `limits`, naming the polygon.
/// Progress phase "elements": polygons subdivided, of all polygons; then "textures" (elements).
BuildResult build_elements(const SceneInput& input, float max_edge, const ElementLimits& limits = {},
                           const ProgressFn& progress = {});

/// The materials' part of build_elements' checks: reflectance in [0, 1), emission finite and not
/// negative, the textures' arrays consistent; InputError naming the polygon. For a caller that
/// reads new materials onto elements built before (bake/cached_transport.cpp).
void validate_materials(const SceneInput& input);

/// The longest edge polygon `polygon`'s elements may have: `max_edge` (0: no bound), or its own
/// smaller one in `polygon_edge` (ElementLimits::polygon_edge, BuildResult::polygon_edge; 0 or
/// absent: none).
float polygon_max_edge(const std::vector<float>& polygon_edge, std::size_t polygon, float max_edge);

/// The diagonal of the points' bounding box, at least 1e-6 (1 for no points): the scale the
/// gaps and lifts of rays are measured against.
float scene_diagonal(const std::vector<Vec3>& points);

}  // namespace radiosity
