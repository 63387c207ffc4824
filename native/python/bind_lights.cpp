/// @file bind_lights.cpp
/// @brief Lamps from Python dicts to the core's Lights, with errors that name the lamp.
#include "bindings.h"

#include <pybind11/stl.h>

#include <cmath>
#include <string>

namespace radiosity::python {

namespace {

/// A 3-vector entry of a lamp dict; ValueError naming the lamp and key when missing or not finite.
glm::dvec3 vector_entry(const py::dict& lamp, const char* key, std::size_t index) {
    if (!lamp.contains(key)) throw InputError("light " + std::to_string(index) + ": missing '" + key + "'");
    std::vector<double> values;
    try {
        values = lamp[key].cast<std::vector<double>>();
    } catch (const py::cast_error&) {
        values.clear();
    }
    if (values.size() != 3 || !std::isfinite(values[0]) || !std::isfinite(values[1]) || !std::isfinite(values[2]))
        throw InputError("light " + std::to_string(index) + ": '" + key + "' must be three finite numbers");
    return {values[0], values[1], values[2]};
}

Vec3 unit_entry(const py::dict& lamp, const char* key, std::size_t index) {
    const glm::dvec3 v = vector_entry(lamp, key, index);
    const double length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(length > 0.0)) throw InputError("light " + std::to_string(index) + ": '" + key + "' has zero length");
    return Vec3(v / length);
}

Rgb colour_entry(const py::dict& lamp, const char* key, std::size_t index) {
    const Rgb c = vector_entry(lamp, key, index);
    if (c.r < 0 || c.g < 0 || c.b < 0)
        throw InputError("light " + std::to_string(index) + ": '" + key + "' is negative");
    return c;
}

/// A non-negative finite number entry, `fallback` when absent.
double size_entry(const py::dict& lamp, const char* key, std::size_t index, double fallback) {
    const double value = lamp.contains(key) ? lamp[key].cast<double>() : fallback;
    if (!(value >= 0.0) || !std::isfinite(value))
        throw InputError("light " + std::to_string(index) + ": '" + key + "' must be a finite number, 0 or more");
    return value;
}

SunLight parse_sun(const py::dict& lamp, std::size_t index) {
    SunLight sun{unit_entry(lamp, "direction", index), colour_entry(lamp, "irradiance", index)};
    sun.half_angle = static_cast<float>(size_entry(lamp, "half_angle", index, 0.0));
    if (!(sun.half_angle < M_PI / 2))
        throw InputError("light " + std::to_string(index) + ": a sun's 'half_angle' must be below pi/2");
    if (lamp.contains("disk_directions")) sun.disk_directions = lamp["disk_directions"].cast<bool>();
    return sun;
}

/// A point or spot lamp's radius and what it is to Cycles: 'shape' SPHERE or DISK (default).
void parse_size(const py::dict& lamp, std::size_t index, PointLight& light) {
    light.radius = static_cast<float>(size_entry(lamp, "radius", index, 0.0));
    const std::string shape = lamp.contains("shape") ? lamp["shape"].cast<std::string>() : "DISK";
    if (shape == "SPHERE")
        light.shape = LampShape::Sphere;
    else if (shape != "DISK")
        throw InputError("light " + std::to_string(index) + ": shape must be 'SPHERE' or 'DISK'");
}

}  // namespace

Lights parse_lights(const py::list& lamps) {
    Lights lights;
    for (std::size_t i = 0; i < lamps.size(); ++i) {
        const py::dict lamp = lamps[i].cast<py::dict>();
        const std::string type = lamp.contains("type") ? lamp["type"].cast<std::string>() : "";
        if (type == "SUN") {
            lights.suns.push_back(parse_sun(lamp, i));
            continue;
        }
        if (type != "POINT" && type != "SPOT")
            throw InputError("light " + std::to_string(i) + ": type must be 'POINT', 'SPOT' or 'SUN'");
        PointLight light;
        light.position = Vec3(vector_entry(lamp, "position", i));
        light.intensity = colour_entry(lamp, "intensity", i);
        parse_size(lamp, i, light);
        if (type == "SPOT") {
            light.direction = unit_entry(lamp, "direction", i);
            const double half_angle = lamp.contains("half_angle") ? lamp["half_angle"].cast<double>() : NAN;
            const double blend = lamp.contains("blend") ? lamp["blend"].cast<double>() : 0.0;
            if (!(half_angle > 0.0 && half_angle <= M_PI / 2 + 1e-6) || !(blend >= 0.0 && blend <= 1.0))
                throw InputError("light " + std::to_string(i) + ": half_angle must be in (0, pi/2], blend in [0, 1]");
            light.cos_half_angle = static_cast<float>(std::cos(half_angle));
            light.smooth = static_cast<float>((1.0 - std::cos(half_angle)) * blend);
            if (lamp.contains("cosine_profile")) light.cosine_profile = lamp["cosine_profile"].cast<bool>();
        }
        lights.points.push_back(light);
    }
    return lights;
}

}  // namespace radiosity::python
