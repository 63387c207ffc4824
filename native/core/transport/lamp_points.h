/// @file lamp_points.h
/// @brief The lamps' irradiance at one point of a surface, soft shadows included (internal).
#pragma once

#include "transport/lights.h"
#include "visibility/ray_tracer.h"

namespace radiosity::detail {

/// Irradiance at `x` on a surface facing `normal` (unit) from every point, spot and sun lamp,
/// each as its kind's own file gives it (point_irradiance, sun_irradiance), the lamps chosen by
/// their unshadowed light there (lamp_choice.h) and the rays seeded by the position of `x`.
Rgb lamp_irradiance(const Lights& lights, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal);

}  // namespace radiosity::detail
