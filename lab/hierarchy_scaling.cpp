#include "hierarchy_scaling.h"

#include "charts.h"
#include "hierarchy/hierarchy.h"
#include "hierarchy_scenes.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace radiosity::charts {
namespace {

using Clock = std::chrono::steady_clock;

/// Longest wait between progress calls (bake start and end included) and its phase.
struct ProgressGaps {
    Clock::time_point last = Clock::now();
    double longest = 0.0;
    std::string phase = "start";
    std::string last_phase = "start";
    std::size_t calls = 0;

    void mark(const char* phase_now) {
        const double gap = seconds_since(last);
        if (gap > longest) {
            longest = gap;
            phase = last_phase + ">" + phase_now;
        }
        last = Clock::now();
        last_phase = phase_now;
        ++calls;
    }
};

/// Side of the cube with the scene's surface area, as the add-on measures a scene (scene_size).
double scene_side(const test::SceneArrays& a) {
    auto vertex = [&](int32_t c) {
        const float* p = &a.positions[3 * std::size_t(a.corner_vertices[c])];
        return glm::dvec3(p[0], p[1], p[2]);
    };
    double area = 0.0;
    for (std::size_t f = 0; f + 1 < a.face_offsets.size(); ++f) {
        const glm::dvec3 o = vertex(a.face_offsets[f]);  // fanned from the first corner
        for (int32_t k = a.face_offsets[f] + 1; k + 1 < a.face_offsets[f + 1]; ++k)
            area += 0.5 * glm::length(glm::cross(vertex(k) - o, vertex(k + 1) - o));
    }
    return std::sqrt(area / 6.0);
}

/// What the add-on's Medium preset asks for: elements of the scene's side / 32, refinement 0.02.
/// The leaves' size follows the scene's extent, not its triangle count: more triangles make
/// more, smaller patches, not finer light on the walls.
HierarchySettings scaling_settings(const LitScene& scene) {
    HierarchySettings s;
    s.min_element_size = float(scene_side(scene.arrays) / 32.0);
    s.lights = scene.lights;
    return s;
}

/// Runs `argv` with stdout into a pipe: returns what it printed and its peak memory in MB.
std::string run_child(const std::vector<std::string>& args, double& peak_mb) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
    const pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], STDOUT_FILENO);
        close(fds[0]);
        close(fds[1]);
        std::vector<char*> argv;
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv("/proc/self/exe", argv.data());
        _exit(127);
    }
    close(fds[1]);
    std::string out;
    char buffer[4096];
    for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) out.append(buffer, std::size_t(n));
    close(fds[0]);
    while (!out.empty() && out.back() == '\n') out.pop_back();
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("child failed: " + out);
    peak_mb = double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
    return out;
}

std::map<std::string, std::string> parse_line(const std::string& line) {
    std::map<std::string, std::string> values;
    std::istringstream in(line);
    for (std::string item; in >> item;) {
        const auto eq = item.find('=');
        if (eq != std::string::npos) values[item.substr(0, eq)] = item.substr(eq + 1);
    }
    return values;
}

}  // namespace

int bake_one(std::size_t triangles, double cancel_after) {
    auto start = Clock::now();
    const LitScene scene = object_room(triangles);
    const double seconds_scene = seconds_since(start);
    ProgressGaps gaps;
    double cancelled_at = -1.0;
    start = Clock::now();
    gaps.last = start;
    const ProgressFn progress = [&](const Progress& p) {
        gaps.mark(p.phase);
        if (cancel_after > 0.0 && seconds_since(start) > cancel_after) {
            if (cancelled_at < 0.0) cancelled_at = seconds_since(start);
            return false;
        }
        return true;
    };
    std::size_t triangle_count = 0;
    for (std::size_t f = 0; f < scene.arrays.material.size(); ++f)
        triangle_count += scene.arrays.face_offsets[f + 1] - scene.arrays.face_offsets[f] == 3;
    const HierarchySettings settings = scaling_settings(scene);
    std::printf("triangles=%zu triangle_edge=%.5f min_element_size=%.4f seconds_scene=%.3f ", triangle_count,
                scene.triangle_edge, settings.min_element_size, seconds_scene);
    try {
        const HierarchyResult r = bake_hierarchical(scene.arrays.input(), settings, progress);
        const double total = seconds_since(start);
        gaps.mark("end");
        const HierarchyStats& s = r.stats;
        std::printf(
            "patches=%zu clusters=%zu leaves=%zu nodes=%zu links=%zu rays=%zu bytes=%zu rounds=%d "
            "iterations=%d cap=%d converged=%d output=%zu seconds=%.3f seconds_elements=%.3f "
            "seconds_links=%.3f seconds_solve=%.3f seconds_interpolate=%.3f progress_calls=%zu "
            "longest_gap=%.3f longest_gap_phase=%s\n",
            s.patches, s.clusters, s.leaves, s.nodes, s.links, s.rays, s.bytes, s.rounds, s.iterations,
            int(s.leaf_cap_reached), int(r.converged), r.output.size(), total, r.seconds_elements, r.seconds_links,
            r.seconds_solve, r.seconds_interpolate, gaps.calls, gaps.longest, gaps.phase.c_str());
    } catch (const Cancelled&) {
        const double thrown = seconds_since(start);
        std::printf(
            "cancel_requested=%.3f cancelled_after=%.3f cancel_latency=%.3f phase=%s progress_calls=%zu "
            "longest_gap=%.3f longest_gap_phase=%s\n",
            cancelled_at, thrown, thrown - cancelled_at, gaps.last_phase.c_str(), gaps.calls, gaps.longest,
            gaps.phase.c_str());
    }
    return 0;
}

void scaling(const std::string& csv_path, const std::vector<std::size_t>& counts, std::size_t cancel_triangles,
             double cancel_after) {
    std::ofstream csv(csv_path);
    const std::vector<std::string> columns = {"triangles",
                                              "triangle_edge",
                                              "min_element_size",
                                              "patches",
                                              "clusters",
                                              "leaves",
                                              "nodes",
                                              "links",
                                              "rays",
                                              "bytes",
                                              "rounds",
                                              "iterations",
                                              "cap",
                                              "converged",
                                              "output",
                                              "seconds",
                                              "seconds_elements",
                                              "seconds_links",
                                              "seconds_solve",
                                              "seconds_interpolate",
                                              "progress_calls",
                                              "longest_gap",
                                              "longest_gap_phase"};
    for (const std::string& c : columns) csv << c << ",";
    csv << "peak_mb\n";
    for (const std::size_t n : counts) {
        double peak_mb = 0.0;
        const std::string line = run_child({"radiosity_hierarchy_charts", "bake_one", std::to_string(n)}, peak_mb);
        std::printf("%s  peak_mb=%.0f\n", line.c_str(), peak_mb);
        std::fflush(stdout);
        auto values = parse_line(line);
        for (const std::string& c : columns) csv << values[c] << ",";
        csv << peak_mb << "\n" << std::flush;
    }
    double peak_mb = 0.0;
    const std::string line = run_child(
        {"radiosity_hierarchy_charts", "bake_one", std::to_string(cancel_triangles), std::to_string(cancel_after)},
        peak_mb);
    std::ofstream(csv_path.substr(0, csv_path.rfind('.')) + "_cancel.txt") << line << " peak_mb=" << peak_mb << "\n";
    std::printf("cancel: %s peak_mb=%.0f\n", line.c_str(), peak_mb);
}

}  // namespace radiosity::charts
