#include "testing/test_util.h"

#include "transport/near_field.h"

#include <algorithm>
#include <cmath>

namespace radiosity::test {

int32_t SceneArrays::add_polygon(const std::vector<Vec3>& corners, const Rgb& rho, const Rgb& emitted,
                                 int32_t material_id) {
    const auto first = static_cast<int32_t>(positions.size() / 3);
    for (std::size_t k = 0; k < corners.size(); ++k) {
        positions.insert(positions.end(), {corners[k].x, corners[k].y, corners[k].z});
        corner_vertices.push_back(first + static_cast<int32_t>(k));
    }
    face_offsets.push_back(static_cast<int32_t>(corner_vertices.size()));
    for (int c = 0; c < 3; ++c) {
        reflectance.push_back(static_cast<float>(rho[c]));
        emission.push_back(static_cast<float>(emitted[c]));
    }
    material.push_back(material_id);
    return static_cast<int32_t>(material.size()) - 1;
}

int32_t SceneArrays::add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, const Rgb& rho, const Rgb& emitted, int32_t material_id) {
    return add_polygon({a, b, c, d}, rho, emitted, material_id);
}

void SceneArrays::add_grid(const Vec3& origin, const Vec3& u, const Vec3& v, int cells, const Rgb& rho,
                           const Rgb& emitted, int32_t material_id) {
    auto at = [&](int i, int j) { return origin + u * (float(i) / float(cells)) + v * (float(j) / float(cells)); };
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j)
            add_quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), rho, emitted, material_id);
}

std::vector<Rgb> fronts(const Elements& e, const std::vector<Rgb>& radiance) {
    std::vector<Rgb> out;
    for (std::size_t i = 0; i < e.size(); ++i)
        if (!e.is_back(i)) out.push_back(radiance[i]);
    return out;
}

std::size_t front_count(const Elements& e) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < e.size(); ++i) count += e.is_back(i) ? 0 : 1;
    return count;
}

SceneInput SceneArrays::input() const {
    SceneInput in;
    in.positions = positions.data();
    in.vertex_count = positions.size() / 3;
    in.face_offsets = face_offsets.data();
    in.corner_vertices = corner_vertices.data();
    in.face_count = material.size();
    in.reflectance = reflectance.data();
    in.emission = emission.data();
    in.material = material.data();
    return in;
}

SceneArrays opposed_unit_squares(float distance, const Rgb& rho, const Rgb& emitted) {
    SceneArrays s;
    const float h = distance;
    s.add_quad({0, 0, h}, {0, 1, h}, {1, 1, h}, {1, 0, h}, Rgb(0), emitted, 1);  // normal -z
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, rho, Rgb(0), 0);      // normal +z
    return s;
}

SceneArrays perpendicular_unit_squares(const Rgb& rho, const Rgb& emitted) {
    SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, rho, emitted, 0);  // z = 0, normal +z
    s.add_quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, rho, emitted, 0);  // x = 0, normal +x
    return s;
}

namespace {
// Adds the six inward-facing sides of the box [lo, hi].
void add_box_inside(SceneArrays& s, Vec3 lo, Vec3 hi, const Rgb& rho, const Rgb& emitted) {
    const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
    s.add_quad({x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, rho, emitted);  // floor, +z
    s.add_quad({x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}, rho, emitted);  // ceiling, -z
    s.add_quad({x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, rho, emitted);  // x = x0, +x
    s.add_quad({x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}, rho, emitted);  // x = x1, -x
    s.add_quad({x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}, rho, emitted);  // y = y0, +y
    s.add_quad({x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, rho, emitted);  // y = y1, -y
}

// Adds the five visible outward-facing sides of a box standing on z = 0 (no bottom).
void add_block(SceneArrays& s, Vec3 lo, Vec3 hi, const Rgb& rho) {
    const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
    const Rgb black(0);
    s.add_quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, rho, black);  // top, +z
    s.add_quad({x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}, rho, black);  // -x
    s.add_quad({x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}, rho, black);  // +x
    s.add_quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, rho, black);  // -y
    s.add_quad({x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}, rho, black);  // +y
}
}  // namespace

SceneArrays closed_box(const Vec3& size, const Rgb& rho, const Rgb& emitted) {
    SceneArrays s;
    add_box_inside(s, Vec3(0), size, rho, emitted);
    return s;
}

SceneArrays cornell_box() {
    SceneArrays s;
    const Rgb white(0.73, 0.73, 0.73), red(0.65, 0.05, 0.05), green(0.12, 0.45, 0.15), black(0);
    const float x0 = 0, y0 = 0, z0 = 0, x1 = 1, y1 = 1, z1 = 1;
    s.add_quad({x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, white, black, 0);  // floor
    s.add_quad({x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}, white, black, 0);  // ceiling
    s.add_quad({x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, red, black, 1);    // left, red
    s.add_quad({x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}, green, black, 2);  // right, green
    s.add_quad({x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, white, black, 0);  // back
    s.add_quad({x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}, white, black, 0);  // front (closed)
    // Ceiling light, a hair below the ceiling, facing down.
    const float lz = z1 - 0.001f;
    s.add_quad({0.4f, 0.4f, lz}, {0.4f, 0.6f, lz}, {0.6f, 0.6f, lz}, {0.6f, 0.4f, lz}, black, Rgb(15.0), 3);
    add_block(s, {0.15f, 0.55f, 0.0f}, {0.45f, 0.85f, 0.6f}, white);
    add_block(s, {0.55f, 0.15f, 0.0f}, {0.85f, 0.45f, 0.3f}, white);
    return s;
}

double worst_direct_light_error(const BakeResult& r, double rho) {
    const Elements& e = r.build.elements;
    double worst = 0.0, peak = 0.0;
    // Receivers: after the emitter, before its back side (emitting polygons are two-sided).
    for (std::size_t i = 1; i < front_count(e); ++i) {
        const double truth = rho * area_flux(e, int32_t(i), 0, 8) / e.area[i];
        peak = std::max(peak, truth);
        worst = std::max(worst, std::abs(r.solve.radiance[i].g - truth));
    }
    return worst / peak;
}

double worst_relative_error(const std::vector<Rgb>& values, const Rgb& expected) {
    double worst = 0.0;
    for (const Rgb& L : values)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(L[c] / expected[c] - 1.0));
    return worst;
}

}  // namespace radiosity::test
