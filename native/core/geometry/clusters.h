/// @file clusters.h
/// @brief The solve's elements chosen by the element size rather than by the faces: small coplanar
/// elements of like surfaces merged into one, whose radiance the faces' elements inherit.
///
/// A finely tessellated wall needs no more unknowns than a coarse one: light is smooth across it.
/// build_elements splits large faces down to the element size but keeps every small face whole, so
/// the solve would follow the tessellation. Here neighbouring elements that share a whole edge, lie
/// in one plane and are the same surface (material, reflectance, emission, side: an emitting
/// polygon's fronts with fronts, its back sides with back sides; no texture, no lamp; the edge
/// between them on no intersection or contact line, Elements::cut_edges) are merged, two at a time,
/// as long as what they form is a convex triangle or quad no longer than the element size, in
/// rounds (triangles into quads, then along each plane's lattice, then any pair that still can): a
/// face grid in any order merges into aligned element-sized rectangles. This is the clustering of
/// Smits, Arvo & Greenberg 1994 ("A clustering algorithm for radiosity in complex environments",
/// SIGGRAPH) and Sillion 1995 ("A unified hierarchical algorithm for global illumination with
/// scattering volumes and object clusters", IEEE TVCG), restricted to coplanar faces: such a
/// cluster is itself a planar polygon, so hemi-cubes, the near field and every transport step treat
/// it as an element and its form factors stay exact in the same sense as an element's. Unlike those
/// papers the clusters are fixed before the solve (no refinement of a cluster into its faces where
/// the light would need it): they are no larger than the element size the bake asks for, which is
/// what the uniform bake resolves anyway.
#pragma once

#include "geometry/scene.h"

#include <cstdint>
#include <vector>

namespace radiosity {

/// The solve's elements and which of them each output element lies in.
struct Clusters {
    /// The solve's elements: merged convex triangles and quads (their edges on cut lines marked in
    /// cut_edges), and every element that was not merged (lamps' and textured faces', those near a
    /// point lamp) as it was. Emitting fronts keep their order before the back sides, as
    /// build_elements orders them. Empty when nothing merged: the output's elements are the solve's.
    Elements elements;
    /// Per output element, its solve element; empty when nothing merged.
    std::vector<int32_t> of_element;

    bool merged() const { return !of_element.empty(); }
};

/// Merges `output`'s small coplanar elements (see the top of this file) into solve elements whose
/// edges are at most `element_size` metres (0: nothing merges). `input` gives each element's
/// material and whether its face is textured. Beside the point lamps at `lamps` a cluster's edges
/// are at most half its members' distance from the nearest: there its light and what the geometry
/// around the lamp lets through (a lamp's fixture) change within that distance. `polygon_edge`: per input
/// polygon, a smaller size its elements merge up to (BuildResult::polygon_edge; 0: `element_size`).
Clusters cluster_elements(const Elements& output, const SceneInput& input, float element_size,
                          const std::vector<Vec3>& lamps = {}, const std::vector<float>& polygon_edge = {});

/// `per_solve` (one value per solve element) read by every output element; `per_solve` itself
/// when nothing merged.
template <typename T>
std::vector<T> per_output_element(const Clusters& clusters, const std::vector<T>& per_solve) {
    if (!clusters.merged()) return per_solve;
    std::vector<T> out(clusters.of_element.size());
    for (std::size_t e = 0; e < out.size(); ++e) out[e] = per_solve[std::size_t(clusters.of_element[e])];
    return out;
}

/// `per_output` (one value per output element, equal within each merged cluster, as the members'
/// material, reflectance and emission are) for the solve elements; `per_output` when nothing merged.
template <typename T>
std::vector<T> per_solve_element(const Clusters& clusters, const std::vector<T>& per_output) {
    if (!clusters.merged()) return per_output;
    std::vector<T> out(clusters.elements.size());
    for (std::size_t e = 0; e < per_output.size(); ++e) out[std::size_t(clusters.of_element[e])] = per_output[e];
    return out;
}

}  // namespace radiosity
