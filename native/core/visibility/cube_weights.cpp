/// @file cube_weights.cpp
/// @brief Exact delta form factors (hemi-cube) and solid angles (full cube) of every cell.
///
/// Both are integrals over a cell, done in closed form rather than sampled at the cell centre:
/// the delta form factor by Lambert's contour formula for a polygon seen from a point,
/// F = 1/(2 pi) sum_i angle(v_i, v_i+1) n . normalize(v_i x v_i+1), and the solid angle by
/// Van Oosterom and Strackee's formula for the cell's two triangles.

#include "visibility/cube_faces.h"
#include "visibility/hemicube.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace radiosity {
namespace {

using DVec3 = glm::dvec3;

/// Form factor from a point with normal (0, 0, 1) to the polygon `corners`, in magnitude.
double lambert_contour(const std::array<DVec3, 4>& corners) {
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) {
        const DVec3 a = glm::normalize(corners[i]), b = glm::normalize(corners[(i + 1) % 4]);
        const DVec3 ab = glm::cross(a, b);
        const double angle = std::atan2(glm::length(ab), glm::dot(a, b));
        sum += angle * glm::normalize(ab).z;
    }
    return std::abs(sum) / (2.0 * M_PI);
}

/// Solid angle of the triangle (a, b, c) seen from the origin (Van Oosterom and Strackee).
double triangle_solid_angle(const DVec3& a, const DVec3& b, const DVec3& c) {
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
    const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    return 2.0 * std::atan2(numerator, denominator);
}

/// The four corners of a cell in local coordinates.
std::array<DVec3, 4> cell_corners(const cube::Layout& layout, int face, int row, int col) {
    const double h = layout.cell_size();
    const double x0 = -1.0 + col * h, y0 = layout.y_min(face) + row * h;
    const std::array<DVec3, 4> on_face{DVec3(x0, y0, 1), DVec3(x0 + h, y0, 1), DVec3(x0 + h, y0 + h, 1),
                                       DVec3(x0, y0 + h, 1)};
    std::array<DVec3, 4> local;
    for (int k = 0; k < 4; ++k) local[k] = DVec3(cube::to_local(cube::faces[face], Vec3(on_face[k])));
    // to_local works in float; the cell corners are dyadic fractions, exact in float for N <= 2^20.
    return local;
}

template <class CellFn>
std::vector<float> per_cell(const cube::Layout& layout, CellFn value) {
    std::vector<float> out(layout.cells());
    for (int f = 0; f < layout.face_count; ++f)
        for (int r = 0; r < layout.rows(f); ++r)
            for (int c = 0; c < layout.resolution; ++c)
                out[layout.offset(f) + std::size_t(r) * layout.resolution + c] =
                    static_cast<float>(value(cell_corners(layout, f, r, c)));
    return out;
}

}  // namespace

std::shared_ptr<const CubeWeights> CubeWeights::make(int resolution) {
    if (resolution < 2 || resolution % 2 != 0 || resolution > 8192)
        throw InputError("hemi-cube resolution must be even and in [2, 8192], got " + std::to_string(resolution));
    auto weights = std::make_shared<CubeWeights>();
    weights->resolution = resolution;
    weights->form_factor = per_cell(cube::hemisphere_layout(resolution), lambert_contour);
    weights->solid_angle = per_cell(cube::sphere_layout(resolution), [](const std::array<DVec3, 4>& c) {
        return triangle_solid_angle(c[0], c[1], c[2]) + triangle_solid_angle(c[0], c[2], c[3]);
    });
    return weights;
}

}  // namespace radiosity
