// Precompiled header of the GoogleTest binaries: the libraries' one plus
// GoogleTest and GoogleMock (see library_pch.h).
#include "library_pch.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
