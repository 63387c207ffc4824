/// @file shared_library.cpp
#include "visibility/shared_library.h"

#ifdef _WIN32
#include <windows.h>
#else
#include <dlfcn.h>
#endif

namespace radiosity::shared_library {

void* open(const std::string& name, std::string& errors) {
#ifdef _WIN32
    void* library = LoadLibraryA(name.c_str());
    if (!library) errors += (errors.empty() ? "" : "; ") + name + ": error " + std::to_string(GetLastError());
#else
    void* library = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) errors += std::string(errors.empty() ? "" : "; ") + dlerror();
#endif
    return library;
}

void* find(void* library, const char* name) {
#ifdef _WIN32
    return reinterpret_cast<void*>(GetProcAddress(static_cast<HMODULE>(library), name));
#else
    return dlsym(library, name);
#endif
}

std::string own_folder() {
#ifdef _WIN32
    HMODULE self = nullptr;
    char path[MAX_PATH] = {};
    if (!GetModuleHandleExA(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                            reinterpret_cast<LPCSTR>(&own_folder), &self) ||
        !GetModuleFileNameA(self, path, MAX_PATH))
        return {};
    const std::string file = path;
#else
    Dl_info info{};
    if (!dladdr(reinterpret_cast<void*>(&own_folder), &info) || !info.dli_fname) return {};
    const std::string file = info.dli_fname;
#endif
    const auto separator = file.find_last_of("/\\");
    return separator == std::string::npos ? std::string() : file.substr(0, separator + 1);
}

}  // namespace radiosity::shared_library
