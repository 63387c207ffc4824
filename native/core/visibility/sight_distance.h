/// @file sight_distance.h
/// @brief The distance at which a scene's surfaces see each other, from a stratified sample of rays.
///
/// Rays leave points spread over the surfaces in proportion to area, in cosine-weighted directions
/// about each element's front: each ray then samples the form factor, so the hits are the elements
/// the light is exchanged with, at the distances it travels. Their mean over a closed convex
/// enclosure is its mean free path 4 V / S (Cauchy's formula for the mean chord; in radiative
/// transfer the mean beam length, Hottel & Sarofim 1967), and it stays the distance between a
/// level's walls however long the level is, where half the bounding box's diagonal grows with it.
#pragma once

#include "geometry/scene.h"

namespace radiosity {

struct SightSettings {
    int points = 2048;   ///< points on the surfaces, stratified by area
    int directions = 8;  ///< rays per point, cosine-weighted about the element's normal
    /// The power mean's exponent. A factor's aliasing error goes as cells^-0.7 (resolution.h), and
    /// the cells an element covers as d^-2, so with the exponent 1.4 the factors' mean relative
    /// error over the rays equals that of every element seen from the returned distance.
    double exponent = 1.4;
    /// Leave out hits nearer than the sending element's size (see sight_distance).
    bool skip_near_hits = true;
};

/// The power mean (SightSettings::exponent) of the hit distances of rays from the elements'
/// centres over their fronts. Rays that leave the scene see nothing, and hits nearer than the
/// sending element's size (sqrt of its area) alias nothing (what lies that near covers a large
/// part of the hemi-cube; the near-field correction replaces those factors): neither counts. Lamps'
/// elements (Elements::lamp) neither send nor stop rays. Half the diagonal of the elements'
/// bounding box when no ray counts (a single plane), 0 without elements.
double sight_distance(const Elements& elements, const SightSettings& settings = {});

/// Half the diagonal of the bounding box of the elements' vertices (0 without any).
double half_diagonal(const Elements& elements);

}  // namespace radiosity
