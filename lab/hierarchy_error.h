/// @file hierarchy_error.h
/// @brief What the artist sees, compared: corner colours interpolated over an element mesh,
/// read at a dense grid of points over every input polygon.
#pragma once

#include "geometry/scene.h"
#include "transport/lights.h"

#include <cstddef>
#include <vector>

namespace radiosity::charts {

/// Points spread evenly over the input polygons, each standing for `weight` square metres.
/// Emitting polygons are left out (their colour is their given emission, never baked).
struct Samples {
    std::vector<Vec3> point;
    std::vector<double> weight;
    std::vector<int32_t> polygon;
    std::vector<Vec3> normal;      ///< the polygon's (Newell's) unit normal
    std::vector<Rgb> reflectance;  ///< the polygon's
};

/// Each polygon fanned into triangles, each triangle cut into n^2 equal triangles with edges of
/// at most `spacing`, one point at each one's centroid.
Samples sample_polygons(const SceneInput& input, float spacing);

/// The colour at each sample: the element of `mesh` (from the sample's polygon) that holds it,
/// its corner colours (4 per element) interpolated barycentrically in triangles and, as Blender
/// shows quads, in the two triangles 0 1 2 and 0 2 3 of a quad. `unlocated` counts samples found in no element (the
/// nearest one is used).
std::vector<Rgb> colours_at(const Samples& samples, const Elements& mesh, const std::vector<Rgb>& element_corner,
                            std::size_t& unlocated);

/// The lamps' first reflection at each sample, rho E / pi, exact: one shadow ray per lamp against
/// `surfaces` (lamp_irradiance_at). Zero without lamps.
std::vector<Rgb> lamp_light_at(const Samples& samples, const Elements& surfaces, const Lights& lights);

/// A reference's colours as the truth: its light without the lamps' first reflection (radiance
/// minus the elements' emission, which holds that reflection; emitters are not sampled),
/// interpolated to its corners and read at the samples, plus the lamps' exact light there.
/// Interpolated element means blur a lamp's sharp shadow over an element; the truth has none.
/// `unlocated` as for colours_at.
std::vector<Rgb> reference_colours(const Samples& samples, const Elements& mesh, const std::vector<Rgb>& radiance,
                                   const int32_t* material, const std::vector<Rgb>& lamp_light, std::size_t& unlocated);

struct ColourError {
    double rms = 0.0;  ///< area-weighted RMS of the colour difference / reference's mean radiance
    double max = 0.0;  ///< largest difference at a sample / reference's mean radiance
};

/// Differences per sample are RMS over the three channels; the mean is of (r + g + b) / 3.
ColourError colour_error(const Samples& samples, const std::vector<Rgb>& got, const std::vector<Rgb>& reference);

}  // namespace radiosity::charts
