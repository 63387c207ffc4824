/// @file sun_raster.h
/// @brief Parallel-projection item buffer for distant (sun) lamps (internal).
#pragma once

#include "transport/lights.h"

namespace radiosity {

/// Adds the sun's irradiance to every element it reaches first along its direction.
/// The scene's silhouette is covered by `resolution` x `resolution` cells.
void add_sun_light(const Elements& elements, const SunLight& sun, int resolution, std::vector<Rgb>& irradiance);

}  // namespace radiosity
