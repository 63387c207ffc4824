/// @file bake.h
/// @brief The whole surface bake: elements, form factors, solve, corner colours.
#pragma once

#include "radiosity/interpolation.h"
#include "radiosity/solver.h"

namespace radiosity {

struct BakeSettings {
    float element_size = 0.0f;       ///< max element edge in metres, 0 = one element per polygon
    int resolution = 128;            ///< hemi-cube cells per full face edge
    SolveSettings solve;
    float hard_edge_angle = 0.5236f; ///< radians (30 degrees)
};

struct BakeResult {
    BuildResult build;
    SolveResult solve;
    CornerColors colors;
    std::size_t matrix_nonzeros = 0;   ///< 0 when rows were rendered on demand
    std::size_t matrix_bytes = 0;
    double seconds_elements = 0, seconds_form_factors = 0, seconds_solve = 0, seconds_interpolate = 0;
};

/// Gauss-Seidel and Jacobi store the matrix; progressive refinement renders rows on demand.
BakeResult bake(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress = {});

}  // namespace radiosity
