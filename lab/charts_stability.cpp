/// @file charts_stability.cpp
/// @brief The stability cases measured here, before and after their mitigation (docs/stability.md):
/// slivers, intersections, contacts, closed-box reciprocity and pin-holes, on the scenes of the
/// tests (test_stability_*.cpp, test_near_field.cpp). The other
/// cases' before and after come from form_factors.csv, aliasing.csv and convergence.csv;
/// plot_native.py joins them into stability_before_after.png.
#include "charts.h"

#include "bake/bake.h"
#include "solve/solver.h"
#include "testing/test_util.h"
#include "transport/form_factors.h"
#include "transport/near_field.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace radiosity::charts {
namespace {

/// Worst |element radiance - exact element mean| / peak on a floor (polygons 1..) under the
/// emitter polygon 0 (radiance 1) with floor reflectance 0.5, one element per polygon.
double worst_element_error(const test::SceneArrays& scene, float max_aspect) {
    BakeSettings s;
    s.resolution = 256;
    s.solve.tolerance = 1e-8;
    s.limits.max_aspect = max_aspect;
    return test::worst_direct_light_error(bake(scene.input(), s), 0.5);
}

/// A 20 cm emitter 30 cm over the floor z = 0, then the floor polygons.
test::SceneArrays lamp_over(const std::vector<std::vector<Vec3>>& floor) {
    test::SceneArrays scene;
    scene.add_quad({0, 0.1f, 0.3f}, {0, 0.3f, 0.3f}, {0.2f, 0.3f, 0.3f}, {0.2f, 0.1f, 0.3f}, Rgb(0), Rgb(1.0));
    for (const auto& polygon : floor) scene.add_polygon(polygon, Rgb(0.5), Rgb(0));
    return scene;
}

std::vector<std::vector<Vec3>> fan() {
    std::vector<std::vector<Vec3>> triangles;
    const Vec3 centre(0.2f, 0.1f, 0.0f);
    for (int k = 0; k < 48; ++k) {
        const double a0 = 2 * M_PI * k / 48, a1 = 2 * M_PI * (k + 1) / 48;
        triangles.push_back({centre, centre + 0.3f * Vec3(std::cos(a0), std::sin(a0), 0),
                             centre + 0.3f * Vec3(std::cos(a1), std::sin(a1), 0)});
    }
    return triangles;
}

/// A 2 x 1 m floor with a black wall through it at x = 0 and a lamp over x < 0: the brightest floor
/// element reaching past the wall / the lit side's mean (test_stability_intersections.cpp).
double wall_leak(bool cut) {
    test::SceneArrays scene;
    scene.add_quad({-1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 1, 0}, Rgb(0.5));
    scene.add_quad({0, 0, -0.5f}, {0, 0, 1.5f}, {0, 1, 1.5f}, {0, 1, -0.5f}, Rgb(0));
    scene.add_quad({-0.7f, 0.3f, 1}, {-0.7f, 0.7f, 1}, {-0.3f, 0.7f, 1}, {-0.3f, 0.3f, 1}, Rgb(0), Rgb(10.0));
    BakeSettings s;
    s.element_size = 0.12f;
    s.resolution = 256;
    s.limits.cut_intersections = cut;
    const BakeResult r = bake(scene.input(), s);
    const Elements& e = r.build.elements;
    double lit = 0.0, area = 0.0, dark = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        if (e.polygon[i] != 0) continue;
        float x_max = -1e9f;
        for (int k = 0; k < 4; ++k) x_max = std::max(x_max, e.vertices[e.corners[i][k]].x);
        if (x_max > 0.0f)
            dark = std::max(dark, r.solve.radiance[i].g);
        else
            lit += e.area[i] * r.solve.radiance[i].g, area += e.area[i];
    }
    return dark / (lit / area);
}

/// A black 0.4 m box standing on a 2 x 2 m floor under a sun straight down (test_stability_contacts.cpp):
/// the brightest floor element reaching under the box, and the worst error of floor elements reaching
/// outside it on the outline, each / the lit floor's exact radiance.
void box_leak(bool cut, double& footprint, double& ring) {
    const float lo = 0.13f, hi = 0.53f, h = 0.4f;
    test::SceneArrays s;
    s.add_quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, Rgb(0.5));
    s.add_quad({lo, lo, 0}, {lo, hi, 0}, {hi, hi, 0}, {hi, lo, 0}, Rgb(0));
    s.add_quad({lo, lo, h}, {hi, lo, h}, {hi, hi, h}, {lo, hi, h}, Rgb(0));
    s.add_quad({lo, lo, 0}, {hi, lo, 0}, {hi, lo, h}, {lo, lo, h}, Rgb(0));
    s.add_quad({hi, lo, 0}, {hi, hi, 0}, {hi, hi, h}, {hi, lo, h}, Rgb(0));
    s.add_quad({hi, hi, 0}, {lo, hi, 0}, {lo, hi, h}, {hi, hi, h}, Rgb(0));
    s.add_quad({lo, hi, 0}, {lo, lo, 0}, {lo, lo, h}, {lo, hi, h}, Rgb(0));
    BakeSettings settings;
    settings.element_size = 0.12f;
    settings.resolution = 64;
    settings.limits.cut_intersections = cut;
    settings.lights.suns.push_back({Vec3(0, 0, -1), Rgb(1.0)});
    const BakeResult r = bake(s.input(), settings);
    const Elements& e = r.build.elements;
    const double lit = 0.5 / M_PI, slack = 1e-5;
    footprint = ring = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        if (e.polygon[i] != 0) continue;
        bool in = false, out = false, on = false;
        for (int k = 0; k < (e.is_triangle(i) ? 3 : 4); ++k) {
            const Vec3& v = e.vertices[e.corners[i][k]];
            const bool beyond = v.x < lo - slack || v.x > hi + slack || v.y < lo - slack || v.y > hi + slack;
            in = in || (v.x > lo + slack && v.x < hi - slack && v.y > lo + slack && v.y < hi - slack);
            out = out || beyond;
            on = on || !beyond;
        }
        const double L = r.solve.radiance[i].g;
        if (in) footprint = std::max(footprint, L / lit);
        if (out && on) ring = std::max(ring, std::abs(L - lit) / lit);
    }
}

/// Furnace at rho 0.99 in a 1 x 1.5 x 0.8 m box, 0.25 m elements, resolution 32: worst |L / L_exact - 1|
/// (test_stability_convergence.cpp).
double pinhole_furnace(bool fill) {
    const Elements e =
        build_elements(test::closed_box(Vec3(1.0f, 1.5f, 0.8f), Rgb(0.99), Rgb(1.0)).input(), 0.25f).elements;
    RowSettings rows;
    rows.resolution = 32;
    rows.fill_pinholes = fill;
    SolveSettings s;
    s.over_relaxation = recommended_over_relaxation(e);
    s.tolerance = 1e-7;
    s.max_iterations = 5000;
    const SolveResult r = solve(e, compute_form_factors(e, rows), s);
    double worst = 0.0;
    for (const Rgb& l : r.radiance) worst = std::max(worst, std::abs(l.g * (1.0 - 0.99) - 1.0));
    return worst;
}

/// Closed 1 x 2 x 1.5 m box at 0.5 m elements: worst |A_i F_ij - A_j F_ji| / A_i (test_near_field.cpp).
double reciprocity(int resolution, bool near_field) {
    const Elements e = build_elements(test::closed_box(Vec3(1, 2, 1.5f), Rgb(0.5), Rgb(0)).input(), 0.5f).elements;
    RowSettings rows;
    rows.resolution = resolution;
    rows.near_field.enabled = near_field;
    const SparseMatrix F = compute_form_factors(e, rows);
    auto entry = [&](std::size_t i, int32_t j) {
        for (int64_t k = F.row_start[i]; k < F.row_start[i + 1]; ++k)
            if (F.col[k] == j) return double(F.val[k]);
        return 0.0;
    };
    double worst = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i)
        for (int64_t k = F.row_start[i]; k < F.row_start[i + 1]; ++k) {
            const int32_t j = F.col[k];
            worst = std::max(
                worst, std::abs(e.area[i] * F.val[k] - e.area[j] * entry(std::size_t(j), int32_t(i))) / e.area[i]);
        }
    return worst;
}

}  // namespace

void stability(const std::string& csv_path) {
    FILE* out = std::fopen(csv_path.c_str(), "w");
    std::fprintf(out, "case,measure,before_setting,after_setting,before,after\n");
    auto row = [&](const char* name, const char* measure, const char* before_setting, const char* after_setting,
                   double before, double after) {
        std::fprintf(out, "%s,%s,%s,%s,%.6e,%.6e\n", name, measure, before_setting, after_setting, before, after);
        std::fflush(out);
    };
    const auto strip = lamp_over({{{0, 0.195f, 0}, {1, 0.195f, 0}, {1, 0.205f, 0}, {0, 0.205f, 0}}});
    const auto needle = lamp_over({{{0, 0.195f, 0}, {1, 0.195f, 0}, {0, 0.205f, 0}}});
    const auto cap = lamp_over({{{0, 0.2f, 0}, {1, 0.2f, 0}, {0.3f, 0.22f, 0}}});
    const auto cylinder_cap = lamp_over(fan());
    const char* element_error = "worst element error / peak";
    row("sliver quad 1 m x 1 cm", element_error, "max_aspect 0", "max_aspect 4", worst_element_error(strip, 0),
        worst_element_error(strip, 4));
    row("needle triangle 1 m x 1 cm", element_error, "max_aspect 0", "max_aspect 4", worst_element_error(needle, 0),
        worst_element_error(needle, 4));
    row("cap triangle 1 m x 2 cm", element_error, "max_aspect 0", "max_aspect 4", worst_element_error(cap, 0),
        worst_element_error(cap, 4));
    row("cylinder cap fan 48 x 7.7:1", element_error, "max_aspect 0", "max_aspect 4",
        worst_element_error(cylinder_cap, 0), worst_element_error(cylinder_cap, 4));
    row("wall through floor 0.12 m", "brightest element past the wall / lit mean", "cut off", "cut on",
        wall_leak(false), wall_leak(true));
    double footprint[2], ring[2];
    box_leak(false, footprint[0], ring[0]);
    box_leak(true, footprint[1], ring[1]);
    row("box on floor 0.12 m", "brightest element under the box / lit", "cut off", "cut on", footprint[0],
        footprint[1]);
    row("box on floor 0.12 m", "worst outline element error / lit", "cut off", "cut on", ring[0], ring[1]);
    for (int n : {64, 256}) {
        const std::string name = "closed box reciprocity res " + std::to_string(n);
        row(name.c_str(), "worst |A_i F_ij - A_j F_ji| / A_i", "near_field off", "near_field on", reciprocity(n, false),
            reciprocity(n, true));
    }
    row("pin-holes res 32", "furnace error at rho 0.99", "fill off", "fill on", pinhole_furnace(false),
        pinhole_furnace(true));
    std::fclose(out);
}

}  // namespace radiosity::charts
