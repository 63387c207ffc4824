/// @file hierarchy_accuracy.h
/// @brief Error of the corner colours against element count, uniform bake vs hierarchy, on the
/// Cornell box and the shadow room, against a converged fine reference.
#pragma once

#include <string>

namespace radiosity::charts {

void accuracy(const std::string& csv_path);

}  // namespace radiosity::charts
