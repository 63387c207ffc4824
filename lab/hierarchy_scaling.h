/// @file hierarchy_scaling.h
/// @brief Hierarchical bakes of object_room at growing triangle counts, each in its own process
/// (its peak memory is the child's ru_maxrss), plus a cancel test.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace radiosity::charts {

/// In this process: builds object_room(triangles), bakes it hierarchically and prints one line
/// "key=value ..." (stats, seconds, longest gap between progress calls). With
/// `cancel_after` > 0 the progress callback cancels after that many seconds and the line says
/// how long the bake took to throw Cancelled.
int bake_one(std::size_t triangles, double cancel_after);

/// Runs bake_one in a child process (this executable, argument "bake_one") for each count and
/// writes one CSV row per count with the child's peak resident memory; then bakes
/// `cancel_triangles` cancelling after `cancel_after` seconds (beside the CSV, *_cancel.txt).
void scaling(const std::string& csv_path, const std::vector<std::size_t>& counts, std::size_t cancel_triangles,
             double cancel_after);

}  // namespace radiosity::charts
