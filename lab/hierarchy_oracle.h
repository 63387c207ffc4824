/// @file hierarchy_oracle.h
/// @brief How few elements the accuracy chart's error levels need at best: the chart's truth
/// itself, taken exactly at the corners of a quadtree over the bake's own patches, refined where
/// its interpolation errs most.
///
/// No bake can do better than its truth at its corners, so the oracle's curve of elements
/// against error bounds what any bake that shows interpolated corner colours on quadtree elements
/// of these patches can reach (the uniform bake and the hierarchy both do). It is looser than
/// any real bake in three ways: its corners are exact, neighbours may disagree at a shared corner
/// (no crack-free output to keep), and it spends each element where the truth says the error is.
#pragma once

#include <string>

namespace radiosity::charts {

/// Writes `csv_path`: per scene and refinement round, the oracle's elements, RMS and max error
/// against the chart's hierarchy reference.
void oracle(const std::string& csv_path);

}  // namespace radiosity::charts
