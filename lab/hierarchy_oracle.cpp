#include "hierarchy_oracle.h"

#include "hierarchy/hierarchy.h"
#include "hierarchy_accuracy.h"
#include "hierarchy_error.h"
#include "hierarchy_locate.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numeric>

namespace radiosity::charts {
namespace {

/// A quadtree element of the oracle: its corners, the truth there, and the samples it holds.
struct Cell {
    std::array<Vec3, 4> corner{};
    int count = 4;  ///< 3 for a triangle
    int32_t polygon = -1;
    Vec3 normal{0.0f};
    Rgb reflectance{0.0};
    std::vector<uint32_t> samples;
    std::array<Rgb, 4> value{};
    double error = 0.0;  ///< sum over its samples of weight x squared difference
};

Vec3 centre_of(const Cell& c) {
    Vec3 sum(0.0f);
    for (int k = 0; k < c.count; ++k) sum += c.corner[k];
    return sum / float(c.count);
}

float longest_edge(const Cell& c) {
    float longest = 0.0f;
    for (int k = 0; k < c.count; ++k)
        longest = std::max(longest, glm::length(c.corner[(k + 1) % c.count] - c.corner[k]));
    return longest;
}

Location locate(const Cell& c, const Vec3& p) {
    const Vec3 u = glm::normalize(glm::cross(c.normal, std::abs(c.normal.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    const Vec3 v = glm::cross(c.normal, u);
    Vec2 q[4];
    for (int k = 0; k < c.count; ++k) q[k] = Vec2(glm::dot(c.corner[k], u), glm::dot(c.corner[k], v));
    const Vec2 at(glm::dot(p, u), glm::dot(p, v));
    return c.count == 3 ? locate_triangle(q, at) : locate_quad(q, at);
}

/// Of the cells `candidates` names, the one that holds `point` (the least outside it).
std::size_t holder(const std::vector<Cell>& cells, const std::vector<std::size_t>& candidates, const Vec3& point) {
    std::size_t best = candidates.front();
    double outside = std::numeric_limits<double>::infinity();
    for (std::size_t k : candidates) {
        const double o = locate(cells[k], point).outside;
        if (o < outside) {
            outside = o;
            best = k;
        }
    }
    return best;
}

/// A cell cut into children with the given corners, the parent's samples shared out.
std::vector<Cell> cut(const Cell& parent, const std::vector<std::vector<Vec3>>& corners, const Samples& samples) {
    std::vector<Cell> children(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) {
        children[i].count = int(corners[i].size());
        std::copy(corners[i].begin(), corners[i].end(), children[i].corner.begin());
        children[i].polygon = parent.polygon;
        children[i].normal = parent.normal;
        children[i].reflectance = parent.reflectance;
    }
    std::vector<std::size_t> all(children.size());
    std::iota(all.begin(), all.end(), std::size_t(0));
    for (uint32_t i : parent.samples) children[holder(children, all, samples.point[i])].samples.push_back(i);
    return children;
}

/// How elongated a cell is: a quad's longer midline over its shorter (1 for a triangle).
float aspect(const Cell& c) {
    if (c.count == 3) return 1.0f;
    const auto& p = c.corner;
    const float a = glm::length((p[1] + p[2]) - (p[3] + p[0])), b = glm::length((p[2] + p[3]) - (p[0] + p[1]));
    return std::max(a, b) / std::min(a, b);
}

/// The ways a cell may split: four children at the edges' midpoints (and a quad's centre); with
/// `binary` also two, a quad cut across either pair of opposite edges (no child more than 8:1)
/// or a triangle at its longest edge's midpoint.
std::vector<std::vector<Cell>> candidate_splits(const Cell& c, bool binary, const Samples& samples) {
    const auto& p = c.corner;
    auto mid = [&](int a, int b) { return (p[a] + p[b]) * 0.5f; };
    std::vector<std::vector<Cell>> splits;
    if (c.count == 3) {
        splits.push_back(cut(c,
                             {{p[0], mid(0, 1), mid(2, 0)},
                              {mid(0, 1), p[1], mid(1, 2)},
                              {mid(2, 0), mid(1, 2), p[2]},
                              {mid(0, 1), mid(1, 2), mid(2, 0)}},
                             samples));
        if (!binary) return splits;
        int k = 0;
        for (int e = 1; e < 3; ++e)
            if (glm::length(p[(e + 1) % 3] - p[e]) > glm::length(p[(k + 1) % 3] - p[k])) k = e;
        const int next = (k + 1) % 3, opposite = (k + 2) % 3;
        splits.push_back(cut(c, {{p[k], mid(k, next), p[opposite]}, {mid(k, next), p[next], p[opposite]}}, samples));
        return splits;
    }
    const Vec3 centre = (p[0] + p[1] + p[2] + p[3]) * 0.25f;
    splits.push_back(cut(c,
                         {{p[0], mid(0, 1), centre, mid(3, 0)},
                          {mid(0, 1), p[1], mid(1, 2), centre},
                          {centre, mid(1, 2), p[2], mid(2, 3)},
                          {mid(3, 0), centre, mid(2, 3), p[3]}},
                         samples));
    if (!binary) return splits;
    for (std::vector<Cell> halves :
         {cut(c, {{p[0], mid(0, 1), mid(2, 3), p[3]}, {mid(0, 1), p[1], p[2], mid(2, 3)}}, samples),
          cut(c, {{p[0], p[1], mid(1, 2), mid(3, 0)}, {mid(3, 0), mid(1, 2), p[2], p[3]}}, samples)})
        if (aspect(halves[0]) <= 8.0f) splits.push_back(std::move(halves));
    return splits;
}

/// The chart's truth: the hierarchy reference's light without the lamps', interpolated, plus the
/// lamps' exact light (reference_colours), at the samples and at any other points.
struct Truth {
    const LitScene& scene;
    const SceneInput& input;
    const Samples& samples;
    const Baked& reference;
    const std::vector<Rgb>& at_samples;
};

/// The truth at the corners of `cells`, each corner a hair inside its cell so that one on a
/// contact line or a shadow edge takes its own side; then each cell's error at its samples.
void take_truth(std::vector<Cell>& cells, const Truth& truth) {
    const Samples& samples = truth.samples;
    Samples corners;
    for (std::size_t c = 0; c < cells.size(); ++c) {
        const Vec3 centre = centre_of(cells[c]);
        for (int k = 0; k < cells[c].count; ++k) {
            corners.point.push_back(cells[c].corner[k] + 1e-4f * (centre - cells[c].corner[k]));
            corners.weight.push_back(0.0);
            corners.polygon.push_back(cells[c].polygon);
            corners.normal.push_back(cells[c].normal);
            corners.reflectance.push_back(cells[c].reflectance);
        }
    }
    const Baked& reference = truth.reference;
    const std::vector<Rgb> lamp = lamp_light_at(corners, reference.mesh, truth.scene.lights);
    std::size_t unlocated = 0;
    const std::vector<Rgb> value =
        reference_colours(corners, reference.mesh, reference.radiance, truth.input.material, lamp, unlocated);
    std::size_t next = 0;
    for (std::size_t c = 0; c < cells.size(); ++c) {
        Cell& cell = cells[c];
        for (int k = 0; k < cell.count; ++k) cell.value[k] = value[next++];
        cell.error = 0.0;
        for (uint32_t i : cell.samples) {
            const Location l = locate(cell, samples.point[i]);
            Rgb got(0.0);
            for (int k = 0; k < cell.count; ++k) got += l.weight[k] * cell.value[k];
            const Rgb d = got - truth.at_samples[i];
            cell.error += samples.weight[i] * glm::dot(d, d) / 3.0;
        }
    }
}

/// The oracle's colour at every sample.
std::vector<Rgb> colours_of(const std::vector<Cell>& cells, const Samples& samples) {
    std::vector<Rgb> colours(samples.point.size(), Rgb(0.0));
    for (const Cell& cell : cells)
        for (uint32_t i : cell.samples) {
            const Location l = locate(cell, samples.point[i]);
            for (int k = 0; k < cell.count; ++k) colours[i] += l.weight[k] * cell.value[k];
        }
    return colours;
}

/// The hierarchy's own patches as the first cells, each with the samples it holds. Emitters
/// are left out (never sampled; each stays one element): their count is returned.
std::size_t patch_cells(const SceneInput& input, const Samples& samples, std::vector<Cell>& cells) {
    const Elements patches = build_elements(input, 0.0f, HierarchySettings().limits).elements;
    std::size_t emitters = 0;
    std::vector<std::vector<std::size_t>> cells_of(input.face_count);
    for (std::size_t e = 0; e < patches.size(); ++e) {
        if (glm::dot(patches.emission[e], Rgb(1.0)) > 0.0) {
            ++emitters;
            continue;
        }
        Cell cell;
        cell.count = patches.is_triangle(e) ? 3 : 4;
        for (int k = 0; k < cell.count; ++k) cell.corner[k] = patches.vertices[patches.corners[e][k]];
        cell.polygon = patches.polygon[e];
        cell.normal = patches.normal[e];
        cell.reflectance = patches.reflectance[e];
        cells_of[cell.polygon].push_back(cells.size());
        cells.push_back(cell);
    }
    for (uint32_t i = 0; i < samples.point.size(); ++i)
        cells[holder(cells, cells_of[samples.polygon[i]], samples.point[i])].samples.push_back(i);
    return emitters;
}

/// One round: the tenth of the cells that err most (squared error summed over their samples),
/// down to two sample spacings, each split the way that removes the most error per element it
/// adds. Returns false when no cell may split.
bool split_worst(std::vector<Cell>& cells, bool binary, const Truth& truth, float spacing) {
    std::vector<std::size_t> chosen;
    for (std::size_t k = 0; k < cells.size(); ++k)
        if (cells[k].samples.size() >= 4 && longest_edge(cells[k]) > 2.0f * spacing) chosen.push_back(k);
    if (chosen.empty()) return false;
    const std::size_t take = std::min(chosen.size(), std::max<std::size_t>(1, cells.size() / 10));
    std::nth_element(chosen.begin(), chosen.begin() + (take - 1), chosen.end(),
                     [&](std::size_t a, std::size_t b) { return cells[a].error > cells[b].error; });
    chosen.resize(take);
    // Every candidate's children take the truth together: [starts[s][k], starts[s][k + 1]) of
    // `trial` are chosen cell s's candidate k.
    std::vector<Cell> trial;
    std::vector<std::vector<std::size_t>> starts(chosen.size());
    for (std::size_t s = 0; s < chosen.size(); ++s)
        for (std::vector<Cell>& children : candidate_splits(cells[chosen[s]], binary, truth.samples)) {
            starts[s].push_back(trial.size());
            for (Cell& child : children) trial.push_back(std::move(child));
        }
    take_truth(trial, truth);
    std::vector<Cell> kept;
    for (std::size_t s = 0; s < chosen.size(); ++s) {
        starts[s].push_back(s + 1 < chosen.size() ? starts[s + 1].front() : trial.size());
        std::size_t best = 0;
        double most = -std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k + 1 < starts[s].size(); ++k) {
            double error = 0.0;
            for (std::size_t t = starts[s][k]; t < starts[s][k + 1]; ++t) error += trial[t].error;
            const double gain = (cells[chosen[s]].error - error) / double(starts[s][k + 1] - starts[s][k] - 1);
            if (gain > most) {
                most = gain;
                best = k;
            }
        }
        for (std::size_t t = starts[s][best]; t < starts[s][best + 1]; ++t) kept.push_back(std::move(trial[t]));
    }
    std::sort(chosen.rbegin(), chosen.rend());
    for (std::size_t k : chosen) {
        cells[k] = std::move(cells.back());
        cells.pop_back();
    }
    for (Cell& child : kept) cells.push_back(std::move(child));
    return true;
}

}  // namespace

void oracle(const std::string& csv_path) {
    std::ofstream csv(csv_path);
    csv << "scene,split,round,elements,rms,max\n";
    for (const AccuracyCase& c : accuracy_cases()) {
        const SceneInput input = c.scene.arrays.input();
        const Samples samples = sample_polygons(input, c.sample_spacing);
        const HierarchyReference reference = hierarchy_reference(c, input, samples);
        const Truth truth{c.scene, input, samples, reference.baked, reference.colours};
        for (bool binary : {false, true}) {
            const char* split = binary ? "anisotropic" : "quadtree";
            std::vector<Cell> cells;
            const std::size_t emitters = patch_cells(input, samples, cells);
            take_truth(cells, truth);
            // Until past 40,000 elements (the finest uniform run has 24,580).
            for (int round = 0;; ++round) {
                const ColourError e = colour_error(samples, colours_of(cells, samples), truth.at_samples);
                csv << c.name << "," << split << "," << round << "," << cells.size() + emitters << "," << e.rms << ","
                    << e.max << "\n"
                    << std::flush;
                std::printf("%-12s %-11s round %2d: %7zu elements  rms %.4f  max %.3f\n", c.name.c_str(), split, round,
                            cells.size() + emitters, e.rms, e.max);
                std::fflush(stdout);
                if (cells.size() > 40000 || !split_worst(cells, binary, truth, c.sample_spacing)) break;
            }
        }
    }
}

}  // namespace radiosity::charts
