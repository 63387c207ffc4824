/// @file hierarchy_accuracy.h
/// @brief Error of the corner colours against element count, uniform bake vs hierarchy, on the
/// Cornell box and the shadow room, against a converged fine reference.
#pragma once

#include "geometry/scene.h"
#include "hierarchy_error.h"
#include "hierarchy_scenes.h"

#include <cstddef>
#include <string>
#include <vector>

namespace radiosity::charts {

/// A series of hierarchical bakes: leaves down to `min_size`, lamp detail `lamp_levels` finer.
struct HierarchySeries {
    std::string method;
    float min_size;
    int lamp_levels;
};

/// One scene's runs: uniform element sizes, hierarchy series over refine tolerances, and the
/// size the two references bake at.
struct AccuracyCase {
    std::string name;
    LitScene scene;
    std::vector<float> sizes;
    std::vector<HierarchySeries> series;
    std::vector<double> refine_tolerances;
    float reference_size;
    int reference_resolution;  ///< the uniform reference's hemi-cube (cornell_wall_means: 256 aliases there)
    float sample_spacing;
};

/// A bake's mesh, radiance and corner colours, how big it is and how long it took.
struct Baked {
    Elements mesh;
    std::vector<Rgb> radiance, corners;
    std::size_t elements = 0, output_elements = 0, links = 0;
    double seconds = 0.0;
};

/// The chart's two scenes with their runs and references.
std::vector<AccuracyCase> accuracy_cases();

/// A hierarchical bake of `scene` as the chart runs it (stats, output mesh, corner colours).
Baked bake_hierarchy(const LitScene& scene, float min_size, int lamp_levels, double refine_tolerance, double tolerance,
                     int rounds);

/// The chart's truth for one case: the hierarchy reference (leaves down to the case's
/// reference size, refine_tolerance 0.005, solved to 1e-6), the lamps' exact light at the
/// samples, and the colours they make there together (reference_colours).
struct HierarchyReference {
    Baked baked;
    std::vector<Rgb> lamp, colours;
    std::size_t unlocated = 0;
};
HierarchyReference hierarchy_reference(const AccuracyCase& c, const SceneInput& input, const Samples& samples);

void accuracy(const std::string& csv_path);

/// The Cornell box's mean radiance per wall from the uniform bake at hemi-cube resolutions 128,
/// 256 and 512 and from the hierarchy at two tolerances: how far the references can be trusted.
void cornell_wall_means();

}  // namespace radiosity::charts
