/// @file hierarchy_error.h
/// @brief What the artist sees, compared: corner colours interpolated over an element mesh,
/// read at a dense grid of points over every input polygon.
#pragma once

#include "radiosity/scene.h"

#include <cstddef>
#include <vector>

namespace radiosity::charts {

/// Points spread evenly over the input polygons, each standing for `weight` square metres.
/// Emitting polygons are left out (their colour is their given emission, never baked).
struct Samples {
    std::vector<Vec3> point;
    std::vector<double> weight;
    std::vector<int32_t> polygon;
};

/// Each polygon fanned into triangles, each triangle cut into n^2 equal triangles with edges of
/// at most `spacing`, one point at each one's centroid.
Samples sample_polygons(const SceneInput& input, float spacing);

/// The colour at each sample: the element of `mesh` (from the sample's polygon) that holds it,
/// its corner colours (4 per element) interpolated barycentrically (triangles) or bilinearly
/// (quads). `unlocated` counts samples found in no element (the nearest one is used).
std::vector<Rgb> colours_at(const Samples& samples, const Elements& mesh, const std::vector<Rgb>& element_corner,
                            std::size_t& unlocated);

struct ColourError {
    double rms = 0.0;  ///< area-weighted RMS of the colour difference / reference's mean radiance
    double max = 0.0;  ///< largest difference at a sample / reference's mean radiance
};

/// Differences per sample are RMS over the three channels; the mean is of (r + g + b) / 3.
ColourError colour_error(const Samples& samples, const std::vector<Rgb>& got, const std::vector<Rgb>& reference);

}  // namespace radiosity::charts
