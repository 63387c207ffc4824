/// @file hierarchy_accuracy.h
/// @brief Error of the corner colours against element count, uniform bake vs hierarchy, on the
/// Cornell box and the shadow room, against a converged fine reference.
#pragma once

#include <string>

namespace radiosity::charts {

void accuracy(const std::string& csv_path);

/// The Cornell box's mean radiance per wall from the uniform bake at hemi-cube resolutions 128,
/// 256 and 512 and from the hierarchy at two tolerances: how far the references can be trusted.
void cornell_wall_means();

}  // namespace radiosity::charts
