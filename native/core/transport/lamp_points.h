/// @file lamp_points.h
/// @brief The lamps' irradiance at one point of a surface, exact: one shadow ray per lamp (internal).
#pragma once

#include "transport/lights.h"
#include "visibility/ray_tracer.h"

namespace radiosity::detail {

/// Irradiance at `x` on a surface facing `normal` (unit) from every point, spot and sun lamp in
/// front of it that nothing hides: I profile cos / r^2, or a sun's irradiance times cos.
Rgb lamp_irradiance(const Lights& lights, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal);

}  // namespace radiosity::detail
