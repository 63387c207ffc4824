/// @file gather_cost.h
/// @brief What the final gather spent, phase by phase: the bake summary's cost line.
#pragma once

#include <cstddef>
#include <cstdint>

namespace radiosity {

/// One phase of the final gather: its wall seconds and the rays it traced (every ray: indirect,
/// shadow rays towards emitters, lamps and the world, probes).
struct GatherPhaseCost {
    double seconds = 0.0;
    std::uint64_t rays = 0;
};

/// The final gather's phases (final_gather.h), in their order. Their seconds add up to the gather's.
struct GatherCost {
    GatherPhaseCost other;     ///< welding, seams, the ray tracer's build; writing the corners
    GatherPhaseCost field;     ///< the field at every element vertex (FinalGatherSettings::field_rays)
    GatherPhaseCost wedges;    ///< the tables of the light around turning vertices
    GatherPhaseCost probes;    ///< the output points' probe rays that decide which are gathered (cache_accuracy)
    GatherPhaseCost points;    ///< the output points: gathered, or their direct light and interpolated indirect
    GatherPhaseCost seams;     ///< the points whose rays met surfaces near them gathered again, and their light solved
    std::size_t gathered = 0;  ///< output points gathered with their own rays
    std::size_t interpolated = 0;  ///< output points whose indirect light was read from gathered ones
    std::size_t buried = 0;        ///< output points left with the interpolated solution (inside geometry)
    std::uint64_t rays() const {
        return other.rays + field.rays + wedges.rays + probes.rays + points.rays + seams.rays;
    }
};

}  // namespace radiosity
