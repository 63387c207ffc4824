/// @file lamp_bubbles.h
/// @brief The lamps' light over an element that the blend of its corners misses, carried by a
/// bubble over it (internal; the final gather).
///
/// The field the gather's rays read blends each element's corner values (corner_blend.h), which
/// holds a light that is linear over the element. A point lamp's light goes as cos / d^2, which is
/// not linear over an element a few times longer than its distance: under a lamp hung over an
/// element's middle the corners miss the peak (a floor face 90 cm under a lamp over its middle: its
/// corners' blend is 0.69 of its light), beyond the lamp's foot the blend lies above the falloff.
/// What a surface reflects into the rays then comes out too dark or too bright. So the field
/// carries, beside the corners, one value per element: the amplitude of a bubble that is zero on the
/// element's edges and one at its centre (27 l0 l1 l2 on a triangle in barycentric coordinates,
/// 16 u (1 - u) v (1 - v) on a quad: the interior shape functions of hierarchical finite elements,
/// Zienkiewicz & Taylor, "The Finite Element Method", vol. 1, ch. 8), that makes the element's mean
/// of each point or spot lamp's light exact: the lamp's exact unshadowed mean over the element
/// (point_polygon_unshadowed: the polygon's solid angle from the lamp) less the blend's mean of its
/// unshadowed light at the corners, times the share of its light that the corners see unhidden,
/// times the element's reflectance / pi. The corners keep their values; the bubble puts what they
/// miss at the element's centre, so the element's light as a whole is right and its place within the
/// element is the bubble's (docs/accuracy.md: a lamp off an element's middle). Each lamp's part is
/// proportional to its power (its shape and shadows are geometry), so the field stays linear in
/// every lamp's strength, as light groups and re-bakes need.
#pragma once

#include "geometry/scene.h"
#include "output/kept_direct_light.h"
#include "transport/lights.h"
#include "visibility/ray_tracer.h"

#include <cstddef>
#include <vector>

namespace radiosity::detail {

/// The means over element e's area of its bubble (element_bubble, corner_blend.h) and of each
/// corner's blend weight (the share of the element's mean each corner value carries): exact for
/// planar quads of any shape.
struct ElementMeans {
    double bubble = 0.0;
    double corner[4] = {0.0, 0.0, 0.0, 0.0};
};
ElementMeans element_means(const Elements& elements, std::size_t e);

/// `field` (4 corner slots an element) with `bubbles` (one an element) after its corner slots.
void append_bubbles(const Elements& elements, const std::vector<Rgb>& bubbles, std::vector<Rgb>& field);

/// Per element, the bubble's amplitude (radiance) that makes the field's mean of the point and spot
/// lamps' reflected light over it exact, 0 where the blend of its corners holds it to within 0.2%.
/// `skip`: elements left as they are (the near lit elements, whose corners keep their solved light).
/// Spots whose profile changes over the element are left out: their cone's edge is not cos / d^2.
/// Shadow rays: each lamp's own soft-shadow rays (point_rays) at the element's corners, only where a
/// bubble is needed, each lamp's light there kept in `kept` (may be null) under its signature in
/// `signatures`, so that a re-bake traces the changed lamps' alone (kept_direct_light.h). Throws
/// Cancelled through `progress` (phase "gather lamp bubbles").
std::vector<Rgb> lamp_bubbles(const Elements& elements, const Lights& lights, const hr::Visibility& visibility,
                              const std::vector<std::size_t>& skip, KeptDirectLight* kept,
                              const SourceSignatures& signatures, const ProgressFn& progress);

}  // namespace radiosity::detail
