// Precompiled header of the `asbuilt` program: the libraries' one plus CLI11,
// which every command file includes (see library_pch.h).
#include "library_pch.h"

#include <CLI/CLI.hpp>
