/// @file shared_library.h
/// @brief Opening a shared library privately and finding functions in it: dlopen and dlsym on
/// Linux and macOS, LoadLibrary and GetProcAddress on Windows.
#pragma once

#include <string>

namespace radiosity::shared_library {

/// The library `name` (a path, or a file name the system looks up), opened with its symbols kept
/// to itself (RTLD_LOCAL); nullptr, with the reason appended to `errors`, if it cannot be opened.
/// Never closed.
void* open(const std::string& name, std::string& errors);

/// The address of the function `name` in `library`, or nullptr.
void* find(void* library, const char* name);

/// The folder of the binary this code is linked into (the Python module), with a trailing
/// separator; empty if the system cannot say.
std::string own_folder();

}  // namespace radiosity::shared_library
