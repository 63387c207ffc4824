/// @file charts.h
/// @brief The chart measurements of radiosity_charts, one CSV each (docs/charts/).
#pragma once

#include <chrono>
#include <string>

namespace radiosity::charts {

/// Chart 1: form-factor error against time per row, hemi-cube resolutions 32..1024, analytic cases.
void form_factors(const std::string& csv_path);
/// Aliasing: RMS error of a small distant patch's factor against resolution and orientations.
void aliasing(const std::string& csv_path);
/// Chart 3: residual against sweep and time for each solver at rho 0.5, 0.9, 0.99.
void convergence(const std::string& csv_path);
/// Stability cases (slivers, intersections, contacts, pin-holes): error before and after the mitigation.
void stability(const std::string& csv_path);

inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace radiosity::charts
