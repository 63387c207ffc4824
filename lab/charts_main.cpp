/// @file charts_main.cpp
/// @brief radiosity_charts OUTPUT_DIR [form_factors|aliasing|convergence|stability ...]: writes the CSVs of
/// the native charts (all of them without names). tools/make_charts.sh runs it and plots.
#include "charts.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>

int main(int argc, char** argv) {
    using namespace radiosity::charts;
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s OUTPUT_DIR [form_factors|aliasing|convergence|stability ...]\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    if (!std::filesystem::is_directory(dir)) {  // the charts would run for minutes and write nothing
        std::fprintf(stderr, "OUTPUT_DIR '%s' is not a folder\n", dir.c_str());
        return 2;
    }
    const std::map<std::string, std::function<void(const std::string&)>> charts{
        {"form_factors", form_factors}, {"aliasing", aliasing}, {"convergence", convergence}, {"stability", stability}};
    std::vector<std::string> names;
    for (int k = 2; k < argc; ++k) names.emplace_back(argv[k]);
    if (names.empty())
        for (const auto& [name, run] : charts) names.push_back(name);
    for (const std::string& name : names) {
        const auto found = charts.find(name);
        if (found == charts.end()) {
            std::fprintf(stderr, "unknown chart '%s'\n", name.c_str());
            return 2;
        }
        const std::string path = dir + "/" + name + ".csv";
        std::printf("%s -> %s\n", name.c_str(), path.c_str());
        found->second(path);
    }
    return 0;
}
