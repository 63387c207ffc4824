/// @file bake.cpp
/// @brief The surface bake pipeline: elements, form factors (stored or on demand), solve, corners.
#include "radiosity/bake.h"

#include <chrono>
#include <memory>

namespace radiosity {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

BakeResult bake(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress) {
    BakeResult result;

    auto start = Clock::now();
    result.build = build_elements(input, settings.element_size);
    const Elements& elements = result.build.elements;
    result.seconds_elements = seconds_since(start);

    // Gathering sweeps read every row each sweep, so they store F; progressive refinement reads
    // each row about once per sweep in shooting order, so it renders rows on demand (memory O(n)).
    start = Clock::now();
    SparseMatrix matrix;
    std::unique_ptr<RowSource> rows;
    if (settings.solve.method == Method::Progressive) {
        rows = std::make_unique<HemicubeRows>(elements, settings.resolution);
    } else {
        matrix = compute_form_factors(elements, settings.resolution, progress);
        result.matrix_nonzeros = matrix.nonzeros();
        result.matrix_bytes = matrix.bytes();
        rows = std::make_unique<StoredRows>(matrix);
    }
    result.seconds_form_factors = seconds_since(start);

    // For progressive refinement this includes rendering the rows it shoots.
    result.solve = solve(elements, *rows, settings.solve, progress);
    result.seconds_solve = result.solve.seconds;

    start = Clock::now();
    result.colors = interpolate_corners(elements, result.solve.radiance, input.material, settings.hard_edge_angle);
    result.seconds_interpolate = seconds_since(start);
    return result;
}

}  // namespace radiosity
